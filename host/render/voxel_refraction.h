// Refraction through the voxels (Chang & Lai, TR 1688 §5 two-surface refraction; Chang et al., PG 2011 §5
// multiple refraction): the scene voxelized every frame on a grid fitted to its bounds with the normal-sum
// and material channels (nothing precomputed), then per pixel that sees a dielectric (kernels/
// refract_voxel.cl):
//   voxel-two    refract at the exact front surface (the visibility buffer's sample, interpolated normal),
//                march the grid to the back surface of that dielectric, refract out with the boundary
//                normal there (voxel or smooth, as for voxel-multi) (or mirror on total internal reflection),
//                then march on to what the ray sees: the first opaque voxel, or the environment on leaving
//                the grid; later dielectrics are passed.
//   voxel-multi  the same front surface, then Snell-law marching: every boundary voxel between media
//                refracts (voxel or smooth normal), the rest of its boundary run is skipped unless a voxel's
//                normal turns more than the angle threshold from the last refraction normal, Beer-Lambert
//                with each medium's absorption, up to VOXR_PATH_MAX_EVENTS interfaces.
// Step rules: the papers' (one voxel along the dominant axis, length h / cos theta) or the 3-D DDA; both skip
// empty VOXR_BRICK^3 bricks (a bit grid built after voxelizing), which the papers do not. An opaque
// voxel ends the path with a VOXR_VOXEL_HIT sample (voxel entry point, voxel normal turned to the ray, the
// voxel's material) that the shadow lookup and shading treat like any surface. The path model is
// kernels/refraction.h's.
#pragma once

#include <memory>

#include "cl/cl_runtime.h"
#include "cl/scratch_buffers.h"
#include "core/triangle_soup.h"
#include "grid/device_voxel_grid.h"
#include "render/camera_frame.h"
#include "render/dielectric_pixels.h"
#include "render/refraction_method.h"
#include "voxelize/device_mesh.h"
#include "voxelize/voxelizer.h"
#include "voxr_layout.h"

namespace voxr {

class VoxelRefraction {
 public:
  // Voxelizes with `voxelizer` (the device's one, shared with the other techniques: one set of scratch
  // buffers).
  VoxelRefraction(ClRuntime& cl, Voxelizer& voxelizer);
  ~VoxelRefraction();

  // Builds (or loads) the voxelizer's and the march's programs.
  void prepare(const RefractionOptions& options);

  // The scene of the next frames (anchor-relative; must stay alive and unchanged until the next set_scene).
  // `scene_mesh` is the soup already on the device (it must stay alive as long): voxelized as it is unless
  // the grid needs triangles split, so the scene has one device copy.
  void set_scene(const TriangleSoup& soup, const DeviceMesh& scene_mesh);

  // Voxelizes the scene on a grid of options.resolution voxels along its longest side (occupancy, normal
  // sum, material), on the device. Throws voxr::Error when no scene was set or the grid does not fit.
  void build(const RefractionOptions& options);

  // Per pixel of `camera` that `dielectric` lists (found from `primary_samples`): its end SurfaceSample and
  // RefractionPath (voxr_layout.h), written at the pixel's index of `end_samples` and `paths` (nothing else
  // is written); materials: material_count RenderMaterial.
  void trace(const CameraFrame& camera, const cl::Buffer& primary_samples, const DielectricPixels& dielectric,
             const cl::Buffer& materials, uint32_t material_count, const RefractionOptions& options,
             cl::Buffer& end_samples, cl::Buffer& paths);

  const DeviceVoxelGrid& grid() const { return grid_; }

 private:
  ClRuntime& cl_;
  Voxelizer& voxelizer_;
  DeviceVoxelGrid grid_;
  const TriangleSoup* soup_ = nullptr;
  Bounds bounds_;                           // the scene's, taken once by set_scene
  const DeviceMesh* scene_mesh_ = nullptr;  // the scene's own device mesh, shared
  std::unique_ptr<DeviceMesh> mesh_;        // split for mesh_grid_, when the grid needs triangles split
  const DeviceMesh* voxelized_ = nullptr;   // mesh_ or scene_mesh_
  GridSpec mesh_grid_;                      // the grid voxelized_ was chosen for
  GrowingBuffer bricks_;                    // one bit per VOXR_BRICK^3 voxels: empty space the march skips
  glm::uvec3 brick_dims_{0};

  VoxelRefractParams params(const RefractionOptions& options) const;
};

}  // namespace voxr
