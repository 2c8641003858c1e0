// One rendered frame with transparent shadows, all on the device: fit the light's grid to what the camera
// can see, voxelize the casters from the light and accumulate transmittance (voxel, uniform), or rasterize
// light-space maps (filter, opaque); rasterize the camera's visibility buffer and resolve it; look up each
// receiver's transmittance; shade. Only the image (and, on request, the samples and their transmittance for
// metrics) is read back. A deforming scene calls set_scene every frame: nothing is precomputed.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "cl/cl_runtime.h"
#include "cl/scratch_buffers.h"
#include "core/material.h"
#include "core/triangle_soup.h"
#include "render/camera_frame.h"
#include "render/dielectric_pixels.h"
#include "render/distance_map_refraction.h"
#include "render/environment_map.h"
#include "render/image_rgba.h"
#include "render/image_space_refraction.h"
#include "render/light_frame.h"
#include "render/light_space_maps.h"
#include "render/refraction_method.h"
#include "render/shadow_method.h"
#include "render/transparent_shadow_map.h"
#include "render/visibility_rasterizer.h"
#include "render/voxel_refraction.h"
#include "voxelize/device_mesh.h"

namespace voxr {

struct RenderOptions {
  ShadowMethod shadows = ShadowMethod::kVoxel;
  uint32_t shadow_resolution = 256;       // columns along the longer side of the light's grid (and its slabs)
  RasterMode mode = RasterMode::kCenter;  // voxel: the light voxelizer's rule
  float bias = kDefaultShadowBias;        // slabs (or depth-map texels) towards the light
  float normal_offset = kDefaultNormalOffset;  // columns off the receiver's surface
  // none, voxel-multi, voxel-two, image-space or distance-maps (the references render on the host:
  // reference_refraction.h)
  RefractionOptions refraction;
  bool keep_samples = false;  // read back the samples, their transmittance and the paths too
};

// Transmittance computed on the host for samples read back (the Embree reference): one RGB per sample.
using HostTransmittance = std::function<std::vector<glm::vec3>(std::span<const SurfaceSample>)>;

struct FrameStats {
  LightFrame light;                        // the light's grid (voxel, uniform, filter, opaque)
  std::map<std::string, double> stage_ms;  // profiled kernel time by stage
  double host_ms = 0.0;                    // host work inside the frame: fitting, projecting, the reference
  double frame_ms = 0.0;                   // wall time of render(), from its start to the image on the host
  uint64_t device_bytes = 0;               // the shadow method's grid or maps
  uint64_t light_triangles = 0;            // triangles voxelized or rasterized from the light
  GridSpec refraction_grid;                // voxel refraction: the scene's grid
  uint64_t refraction_bytes = 0;  // the refraction method's structure: the voxel grid's channels, the
                                  // image-space buffers or the distance-map layers
};

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

  // Builds (or loads) every program a frame with `options` runs.
  void prepare(const RenderOptions& options);

  // The scene of the next frames: triangles (anchor-relative; a CPU device reads them in place, so `soup`
  // must stay alive and unchanged until the next set_scene), materials and angle-weighted vertex normals.
  // Throws voxr::Error for a material id out of range.
  void set_scene(const TriangleSoup& soup, const std::vector<Material>& materials);

  // What rays leaving the scene see (uploaded once). Without it, a constant environment of the light's
  // ambient colour.
  void set_environment(const EnvironmentMap& environment);
  // Wyman's d_N per vertex of the scene's soup (inward_distances), needed by image-space refraction.
  void set_inward_distances(const std::vector<float>& d_n);

  // Renders one frame. `host_transmittance` is required for ShadowMethod::kReference. Throws voxr::Error for
  // a host-side refraction method (the references).
  RenderedFrame render(const RenderLight& light, const CameraFrame& camera, const RenderOptions& options,
                       const HostTransmittance& host_transmittance = {}, FrameStats* stats = nullptr);

 private:
  ClRuntime& cl_;
  VisibilityRasterizer rasterizer_;
  TransparentShadowMap shadow_map_;
  LightSpaceMaps light_maps_;
  VoxelRefraction voxel_refraction_;
  ImageSpaceRefraction image_space_;
  DistanceMapRefraction distance_maps_;
  DielectricPixels dielectric_pixels_;
  const TriangleSoup* soup_ = nullptr;
  std::vector<Material> materials_;
  uint32_t material_count_ = 0;
  std::unique_ptr<DeviceMesh> mesh_;
  cl::Buffer materials_buffer_, vertex_normals_;
  GrowingBuffer visibility_, samples_, transmittance_, image_, ends_, paths_;
  cl::Buffer environment_;
  glm::uvec2 environment_size_{0, 0};
  bool environment_given_ = false;
  bool inward_distances_set_ = false;
  bool scene_has_dielectric_ = false;  // a triangle of the scene is a dielectric: refraction has work

  void upload_environment(const EnvironmentMap& environment);
};

}  // namespace voxr
