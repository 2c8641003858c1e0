// Refraction through the voxels (Chang & Lai, TR 1688 §5 two-surface refraction; Chang et al., PG 2011 §5
// multiple refraction): the scene voxelized every frame with the normal-sum and material channels (nothing
// precomputed) on two levels (RefractionGrid::kFitted): a fine grid over the dielectric triangles' bounds
// with kFineMarginVoxels around them, options.resolution voxels along its longest side, into which every
// scene triangle that meets it is voxelized; and a coarse grid over the whole scene (and the fine box),
// options.coarse_resolution voxels along its longest side, that the march goes on in after leaving the
// fine box (straight on: every dielectric lies in the fine box, so the coarse level has no refraction
// events and a path never comes back). RefractionGrid::kScene (the papers): one grid over the whole scene,
// options.resolution along its longest side. Then per pixel that sees a dielectric (kernels/
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
// voxel's material) that the shadow lookup and shading treat like any surface. Where surfaces of several
// materials share a voxel the voxelizer keeps the highest material id (atomic max): the levels are voxelized
// with each material's rank by kind (dielectrics, then sheets, then opaque; by index within a kind) as its
// id, so an opaque surface coincident with glass wins (issue 19), and the march maps ranks back to
// materials. The path model is kernels/refraction.h's.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "cl/cl_runtime.h"
#include "cl/scratch_buffers.h"
#include "core/material.h"
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

  // Fine grid margin around the dielectrics' bounds, in fine voxels.
  static constexpr float kFineMarginVoxels = 2.0f;

  // The scene of the next frames (anchor-relative; must stay alive and unchanged until the next set_scene);
  // `materials` are its materials (triangle material ids index them; the dielectrics' bounds come from
  // them). `scene_mesh` is the soup already on the device (it must stay alive as long): voxelized as it is
  // unless a grid needs triangles split, so the scene has one device copy.
  void set_scene(const TriangleSoup& soup, const DeviceMesh& scene_mesh,
                 const std::vector<Material>& materials);

  // The grids options.grid asks for on this scene (anchor-relative): the fine level and, for kFitted on a
  // scene with dielectric triangles, the coarse one (else nullopt: the fine level is the whole scene's
  // grid). Throws voxr::Error when no scene was set or a grid does not fit.
  struct Levels {
    GridSpec fine;
    std::optional<GridSpec> coarse;
  };
  Levels grids(const RefractionOptions& options) const;

  // Voxelizes the scene on grids(options) (occupancy, normal sum, material), on the device. Throws
  // voxr::Error when no scene was set or a grid does not fit.
  void build(const RefractionOptions& options);

  // Per pixel of `camera` that `dielectric` lists (found from `primary_samples`): its end SurfaceSample and
  // RefractionPath (voxr_layout.h), written at the pixel's index of `end_samples` and `paths` (nothing else
  // is written); materials: material_count RenderMaterial.
  void trace(const CameraFrame& camera, const cl::Buffer& primary_samples, const DielectricPixels& dielectric,
             const cl::Buffer& materials, uint32_t material_count, const RefractionOptions& options,
             cl::Buffer& end_samples, cl::Buffer& paths);

  // The last build's fine level, and its coarse level (null when it had none).
  const DeviceVoxelGrid& grid() const { return fine_.grid; }
  const DeviceVoxelGrid* coarse_grid() const { return coarse_present_ ? &coarse_.grid : nullptr; }
  // Device bytes of both levels' grids.
  uint64_t device_bytes() const;

 private:
  // One level: its grid, the mesh voxelized into it and its empty-space bricks.
  struct Level {
    DeviceVoxelGrid grid;
    std::unique_ptr<DeviceMesh> mesh;       // split for mesh_grid, when the grid needs triangles split
    const DeviceMesh* voxelized = nullptr;  // mesh or the scene's mesh
    GridSpec mesh_grid;                     // the grid `voxelized` was chosen for
    GrowingBuffer bricks;                   // one bit per VOXR_BRICK^3 voxels: empty space the march skips
    glm::uvec3 brick_dims{0};
  };

  ClRuntime& cl_;
  Voxelizer& voxelizer_;
  Level fine_, coarse_;
  bool coarse_present_ = false;
  const TriangleSoup* soup_ = nullptr;
  Bounds bounds_;                           // the scene's, taken once by set_scene
  Bounds dielectric_bounds_;                // its dielectric triangles' (empty: none)
  const DeviceMesh* scene_mesh_ = nullptr;  // the scene's own device mesh, shared, or ranked_mesh_
  // When the scene's material order is not already by kind: its soup with ids replaced by ranks, on the
  // device; otherwise empty and the scene's own soup and mesh are voxelized.
  TriangleSoup ranked_soup_;
  std::unique_ptr<DeviceMesh> ranked_mesh_;
  GrowingBuffer material_of_;  // uint per rank: the material index

  void build_level(Level& level, const GridSpec& spec);
  VoxelRefractParams params(const RefractionOptions& options) const;
};

}  // namespace voxr
