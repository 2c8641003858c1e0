// The image-space baseline: Wyman 2005, "An Approximate Image-Space Approach for Interactive Refraction"
// (SIGGRAPH) with nearby geometry (Wyman, "Interactive Image-Space Refraction of Nearby Geometry", GRAPHITE
// 2005). Per pixel that sees a dielectric:
//   1. refract the camera ray at the front surface (the primary sample: exact position, interpolated normal);
//   2. d_V = back-face depth - front depth along the view ray (back faces of the dielectrics rasterized by
//      the kernel rasterizer, nearest kept), d_N = the front hit's interpolated per-vertex inward distance
//      (reference/inward_distance.h); d = (theta_t / theta_i) d_V + (1 - theta_t / theta_i) d_N;
//   3. P2 = P1 + d T1; project P2, read the back-face buffer's normal there, refract out (total internal
//      reflection mirrors);
//   4. nearby geometry: the opaque surfaces' own visibility buffer (rasterized without dielectrics), searched
//      along the exit ray by the paper's iterative lookup (project the current guess, read the opaque
//      position there, move the guess to its distance; a fixed number of iterations); a ray that leaves the
//      image or finds no opaque surface sees the environment.
// Outputs the same end samples and RefractionPath records as the voxel methods (voxr_layout.h); Schlick F at
// the first surface, 1 - F at each of the two refractions, Beer-Lambert over d (the front dielectric's ior
// and absorption throughout). Every refracting pixel records 2 events (VOXR_PATH_TIR where the exit mirrors)
// and exit_position P2; an opaque end is the opaque buffer's resolved sample with its normals turned against
// the exit ray. Details and fallbacks (kernels/image_space.cl):
//   - at normal incidence (theta_i < 1e-3) the blend uses its limit theta_t / theta_i -> 1 / ior;
//   - no back face at the pixel, or one not behind the front: d = d_N; no d_N (inward_distances shorter than
//     the mesh's vertices): d = d_V;
//   - P2 off the image or on a pixel without a back face: the back face at the pixel itself; none there
//     either: the ray leaves along T1 with 1 - F0;
//   - the lookup's first guess is the distance from P2 to the opaque sample at P2's pixel, else the size of
//     the mesh's bounds; kImageSpaceIterations (4) lookups; the last one's sample is the end.
#pragma once

#include <vector>

#include "cl/cl_runtime.h"
#include "cl/scratch_buffers.h"
#include "render/camera_frame.h"
#include "render/dielectric_pixels.h"
#include "render/visibility_rasterizer.h"
#include "voxelize/device_mesh.h"

namespace voxr {

class ImageSpaceRefraction {
 public:
  ImageSpaceRefraction(ClRuntime& cl, VisibilityRasterizer& rasterizer);

  // The programs trace() runs (besides the rasterizer's).
  std::vector<ProgramSpec> programs() const;

  // d_N per vertex of the scene's mesh (inward_distances), uploaded once per scene.
  void set_inward_distances(const std::vector<float>& d_n);

  // For every pixel of `camera` that `dielectric` lists (found from `primary_samples`, resolved from the
  // camera's full visibility buffer): its end SurfaceSample and RefractionPath (voxr_layout.h), written at
  // the pixel's index of `end_samples` and `paths` (nothing else is written). `mesh` and `vertex_normals` as
  // FrameRenderer has them; materials: material_count RenderMaterial.
  void trace(const DeviceMesh& mesh, const cl::Buffer& vertex_normals, const CameraFrame& camera,
             const cl::Buffer& materials, uint32_t material_count, const cl::Buffer& primary_samples,
             const DielectricPixels& dielectric, cl::Buffer& end_samples, cl::Buffer& paths);

  // Device memory of d_N and the back-face and opaque buffers (as allocated, after a trace).
  uint64_t device_bytes() const {
    return inward_distance_.bytes + back_visibility_.bytes + back_samples_.bytes + opaque_visibility_.bytes +
           opaque_samples_.bytes;
  }

 private:
  ClRuntime& cl_;
  VisibilityRasterizer& rasterizer_;
  GrowingBuffer inward_distance_, back_visibility_, back_samples_, opaque_visibility_, opaque_samples_;
  uint32_t inward_count_ = 0;
};

// The nearby-geometry lookups per pixel (Wyman's fixed iteration count).
inline constexpr uint32_t kImageSpaceIterations = 4;

}  // namespace voxr
