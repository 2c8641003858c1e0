// Layered distance maps: Umenhoffer, Patow, Szirmay-Kalos, "Robust Multiple Specular Reflections and
// Refractions", GPU Gems 3, chapter 17 (2007). Every frame, from a reference point (the centre of the
// dielectric triangles' bounds), the kernel rasterizer renders cube maps of 6 faces of layer_res^2 texels
// (90-degree cameras, faces as VOXR_CUBE_FACES in voxr_layout.h):
//   - the refractor's layers: the dielectric triangles only, depth-peeled (rasterize_depth_peel): layer l
//     holds the (l+1)-th nearest surface along each texel's ray, resolved to a SurfaceSample (distance from
//     the reference point, smooth shading normal, material);
//   - the diffuse environment layer: the nearest opaque or sheet surface per texel, resolved like the
//     camera's visibility buffer, so a path ending on it is shaded and shadowed like the other methods' ends.
// Tracing (kernels/distance_maps.cl, one work item per pixel): refract at the exact front surface
// (rp_front_surface); per segment, a linear search along the ray in kDistanceMapSearchSteps steps compares
// each ray point's distance from the reference point with each layer's stored distance in its direction; a
// sign change is refined by kDistanceMapSecantSteps secant steps and accepted where the refined gap is
// within a search step plus two texels' footprint (else it was a depth discontinuity of the layer). The
// nearest layer hit refracts (or mirrors on total internal reflection) by refraction.h's model: 1 - F
// (Schlick) per refraction, Beer-Lambert per segment inside, media on media_stack.h's stack (entered or left
// by the winding of the triangle a layer holds: trace reads the mesh's positions and triangles); an
// environment-layer hit ends the path there. Outside every medium the search continues, environment layer
// only, to the scene's bounding sphere; nothing found is the environment. Failures the method has by
// construction, not hidden: a surface hidden from the reference point behind `layers` others, or an opaque
// surface hidden behind another from it, is not found (a path inside glass that finds no surface is
// VOXR_PATH_LOST); surfaces closer than a search step apart along a ray may be skipped; max_events ends a
// path VOXR_PATH_LOST. A camera inside a dielectric is refused (trace throws): every path starts by entering
// the first surface seen, and the maps hold no surface beyond the refractor for a path that leaves it, so the
// picture would be dark (issue 20, kind 6).
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "cl/cl_runtime.h"
#include "cl/scratch_buffers.h"
#include "core/material.h"
#include "core/triangle_soup.h"
#include "render/camera_frame.h"
#include "render/dielectric_pixels.h"
#include "render/refraction_method.h"
#include "render/visibility_rasterizer.h"
#include "voxelize/device_mesh.h"

namespace voxr {

// Linear search steps per segment and secant refinement steps (the chapter's search; fixed).
inline constexpr uint32_t kDistanceMapSearchSteps = 64;
inline constexpr uint32_t kDistanceMapSecantSteps = 8;
// Peeling: a fragment is a new layer when its depth exceeds the previous layer's by more than this many
// float steps (about 2.4e-4 of the refractor's radius at its surface with the near plane used).
inline constexpr uint32_t kDistanceMapPeelUlps = 4;
// Ranges `voxr render` accepts.
inline constexpr uint32_t kDistanceMapMaxLayers = 16;
inline constexpr uint32_t kDistanceMapMinRes = 8, kDistanceMapMaxRes = 2048;

// Where the cube maps stand, from the scene: the reference point (anchor-relative) and the radii of the
// spheres about it that hold the dielectric triangles and the whole scene. Without dielectrics: the scene's
// bounds stand in.
struct DistanceMapOrigin {
  glm::vec3 reference{0.0f};
  float radius = 1.0f;
  float scene_radius = 1.0f;
};
DistanceMapOrigin distance_map_origin(const TriangleSoup& soup, const std::vector<Material>& materials);

// The dielectric material whose closed surface holds `point` (anchor-relative), by the media stack's winding
// rule (kernels/common/media_stack.h): the first material whose triangles a ray from `point` (a fixed
// direction off every axis) leaves more often than it enters (by their winding); where it enters more (an
// open or inside-out mesh), an odd number of crossings. nullopt when there is none. Exact for closed meshes
// wound outwards; an open sheet of dielectric counts by the side the ray leaves.
std::optional<uint32_t> dielectric_around(const TriangleSoup& soup, const std::vector<Material>& materials,
                                          const glm::vec3& point);

// The camera of cube face `face` (0..5: +x, -x, +y, -y, +z, -z) at `eye`: 90 degrees, `res` x `res` texels,
// view depths near..far.
CameraFrame cube_face_frame(const glm::vec3& eye, uint32_t face, uint32_t res, float near_plane,
                            float far_plane);

class DistanceMapRefraction {
 public:
  // Its rasterizer names all its kernels "dm-layers" in the profiler; tracing is "refraction".
  explicit DistanceMapRefraction(ClRuntime& cl);

  std::vector<ProgramSpec> programs() const;

  // The scene of the next frames (as FrameRenderer::set_scene has it): places the reference point.
  void set_scene(const TriangleSoup& soup, const std::vector<Material>& materials);

  // Renders the layers (options.layers refractor layers and the environment layer, options.layer_res^2
  // texels per face) and traces every pixel of `camera` that `dielectric` lists (found from
  // `primary_samples`): its end SurfaceSample and RefractionPath, written at the pixel's index of
  // `end_samples` and `paths` (nothing else is written).
  // `mesh`, `vertex_normals`, `materials` (material_count RenderMaterial) as FrameRenderer has them. Throws
  // voxr::Error for layers or layer_res out of range, and when the camera's eye is inside a dielectric of the
  // scene (dielectric_around): the method traces from outside the refractor.
  void trace(const DeviceMesh& mesh, const cl::Buffer& vertex_normals, const CameraFrame& camera,
             const cl::Buffer& materials, uint32_t material_count, const RefractionOptions& options,
             const cl::Buffer& primary_samples, const DielectricPixels& dielectric, cl::Buffer& end_samples,
             cl::Buffer& paths);

  // Device memory of the layers and the buffers that build them (as allocated, after a trace).
  uint64_t device_bytes() const {
    return peel_[0].bytes + peel_[1].bytes + face_samples_.bytes + layers_.bytes + environment_.bytes +
           distances_.bytes;
  }

 private:
  ClRuntime& cl_;
  VisibilityRasterizer rasterizer_;
  DistanceMapOrigin origin_;
  // The scene's dielectric triangles (3 anchor-relative corners each, and its material id) and the
  // materials' names, for the camera-inside check.
  std::vector<glm::vec3> dielectric_corners_;
  std::vector<uint32_t> dielectric_materials_;
  std::vector<std::string> material_names_;
  // The eye the check last passed for this scene: a still camera is not checked again every frame (the
  // check walks every dielectric triangle on the host).
  std::optional<glm::vec3> outside_eye_;
  RasterBins bins_;
  GrowingBuffer peel_[2], face_samples_, layers_, environment_, distances_;

  // Resolves `visibility` for `frame` and copies it to `out` at SurfaceSample `first`.
  void resolve_into(const DeviceMesh& mesh, const cl::Buffer& vertex_normals, const CameraFrame& frame,
                    const cl::Buffer& visibility, cl::Buffer& out, uint64_t first);
};

}  // namespace voxr
