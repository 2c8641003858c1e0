// One rendered frame through the technique seam (render/technique.h), with no switch over methods: the
// shadow technique builds its light-space structure; the camera's visibility buffer is rasterized and
// resolved into the primary samples; the refraction technique traces every pixel's path to its end; the
// shadow technique looks up the transmittance at the ends; shade. A technique that finishes the frame on the
// host (the Embree references) replaces the last four steps. Only the image (and, on request, the samples,
// their transmittance and the paths for metrics) is read back. A deforming scene calls set_scene every
// frame; the techniques redo their per-scene setup there.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cl/cl_runtime.h"
#include "cl/scratch_buffers.h"
#include "core/material.h"
#include "core/triangle_soup.h"
#include "render/camera_frame.h"
#include "render/dielectric_pixels.h"
#include "render/environment_map.h"
#include "render/refraction_method.h"
#include "render/scene_reference.h"
#include "render/shadow_method.h"
#include "render/technique.h"
#include "render/triangle_grid.h"
#include "render/visibility_rasterizer.h"
#include "util/image_rgba.h"
#include "voxelize/device_mesh.h"
#include "voxelize/voxelizer.h"

namespace voxr {

struct RenderedFrame {
  ImageRgba image;
  // keep_samples: one per pixel, row 0 at the top: where each pixel's path ends (the primary sample where
  // it meets no dielectric), the shadow method's transmittance from there, the path
  std::vector<SurfaceSample> samples;
  std::vector<glm::vec3> transmittance;
  std::vector<RefractionPath> paths;
};

class FrameRenderer {
 public:
  explicit FrameRenderer(ClRuntime& cl);
  ~FrameRenderer();

  // Builds (or loads) every program a frame with `options` runs, and makes its two techniques (registry
  // factories, render/technique.h) if this renderer has not made them yet.
  void prepare(const RenderOptions& options);

  // The scene of the next frames: triangles (anchor-relative; a CPU device reads them in place, so `soup`
  // must stay alive and unchanged until the next set_scene), materials and angle-weighted vertex normals.
  // `reference` (optional; must outlive the frames of this scene) is the exact reference the reference
  // techniques and image-space's d_N ask (reference/embree_reference.h). Every technique made so far redoes
  // its per-scene setup here (others on their first frame). Throws voxr::Error for a material id out of
  // range, or what a technique's setup throws (image-space without a reference).
  void set_scene(const TriangleSoup& soup, const std::vector<Material>& materials,
                 SceneReference* reference = nullptr);

  // What rays leaving the scene see (uploaded once). Without it, a constant environment of the light's
  // ambient colour.
  void set_environment(const EnvironmentMap& environment);

  // Renders one frame with options.shadows and options.refraction. Throws voxr::Error when a technique
  // needs the reference and set_scene was given none, or when a host-finished refraction (the references)
  // is paired with other shadows than the reference's.
  RenderedFrame render(const RenderLight& light, const CameraFrame& camera, const RenderOptions& options,
                       FrameStats* stats = nullptr);

  // The techniques made so far (prepare or the first frame using them), for their device bytes and
  // descriptions. Throws InternalError for one not made.
  const ShadowTechnique& shadow_technique(ShadowMethod method) const;
  const RefractionTechnique& refraction_technique(RefractionMethod method) const;

 private:
  ClRuntime& cl_;
  VisibilityRasterizer rasterizer_;
  DielectricPixels dielectric_pixels_;
  Voxelizer voxelizer_;  // the device's one, shared by the techniques that voxelize (made before them)
  TriangleGrids triangle_grids_;  // the exact techniques' triangle lists, rebuilt every frame
  std::map<ShadowMethod, std::unique_ptr<ShadowTechnique>> shadows_;
  std::map<RefractionMethod, std::unique_ptr<RefractionTechnique>> refractions_;
  std::map<const void*, bool> scene_set_;  // technique -> its per-scene setup ran for the current scene
  FrameContext ctx_;                       // the scene's members; the frame's are set inside render()
  const TriangleSoup* soup_ = nullptr;
  std::vector<Material> materials_;
  std::vector<glm::vec3> host_normals_;
  std::unique_ptr<DeviceMesh> mesh_;
  cl::Buffer materials_buffer_, vertex_normals_;
  GrowingBuffer visibility_, samples_, transmittance_, image_, ends_, paths_;
  cl::Buffer environment_;
  glm::uvec2 environment_size_{0, 0};
  std::optional<EnvironmentMap> environment_map_;  // host copy for the techniques
  bool environment_given_ = false;
  glm::vec3 ambient_{0.0f};  // without set_environment: the ambient colour the uploaded environment holds
  bool scene_has_dielectric_ = false;  // a triangle of the scene is a dielectric: refraction has work

  // One try at the frame render() asks for, its stats (but the time and syncs of all tries) into `st`.
  RenderedFrame render_once(const RenderLight& light, const CameraFrame& camera, const RenderOptions& options,
                            FrameStats& st);
  void upload_environment(const EnvironmentMap& environment);
  ShadowTechnique& shadow(ShadowMethod method);
  RefractionTechnique& refraction(RefractionMethod method);
  // Runs the technique's per-scene setup once per scene.
  template <class Technique>
  void ensure_scene(Technique& technique);
};

}  // namespace voxr
