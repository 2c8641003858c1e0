// Exact surfaces inside the voxels (issue 19 item 2; beyond the papers): per boundary voxel, the triangles
// that touch it, built on the device every frame from the conservative voxelizer (count -> scan -> fill,
// VoxelizeOptions::triangle_lists) on a grid fitted to the mesh's bounds. Conservative mode's guaranteed
// superset — every triangle that touches a voxel is listed in it — is what lets a march through the lists
// (kernels/common/triangle_grid.h tg_nearest_hit) find every hit, so the exact techniques (refraction and
// shadows `voxel-exact`) intersect the true triangles at any resolution. Nothing is precomputed: a static
// scene is rebuilt every frame like a deforming one.
//
//   TriangleGrid   one grid of lists at one resolution (occ + count + rank index + offsets + ids).
//   TriangleGrids  the frame's cache by resolution, owned by FrameRenderer (FrameContext::triangle_grids):
//                  begin_frame() marks every grid stale, get() builds a stale one, so both exact techniques
//                  of a frame share one build.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include "cl/cl_runtime.h"
#include "grid/device_voxel_grid.h"
#include "voxelize/device_mesh.h"
#include "voxelize/voxelizer.h"

namespace voxr {

// The arguments of a kernel's VOXR_TRIANGLE_GRID_PARAMS (kernels/common/triangle_grid.h), for
// ClRuntime::launch: the grid view, the list offsets (voxels_set + 1 ulong) and ids (uint, `capacity`
// entries), the mesh's positions (float4, anchor-relative world) and triangles (uint4: indices, material),
// and the empty-space bits (one per VOXR_BRICK^3 voxels, brick_dims per axis, x fastest).
struct TriangleGridArgs {
  GridViewArgs grid;
  const cl::Buffer* offsets = nullptr;
  const cl::Buffer* ids = nullptr;
  cl_ulong capacity = 0;
  const cl::Buffer* positions = nullptr;
  const cl::Buffer* triangles = nullptr;
  const cl::Buffer* bricks = nullptr;
  cl_uint4 brick_dims{};
  void set_kernel_args(cl::Kernel& kernel, cl_uint& index) const;
};

class TriangleGrid {
 public:
  // Builds with `voxelizer` (the device's one: one set of scratch buffers).
  TriangleGrid(ClRuntime& cl, Voxelizer& voxelizer);

  // What build() asks the voxelizer for: hybrid, conservative, occ + count, triangle lists. Build its
  // programs with Voxelizer::prepare(voxelize_options()).
  static VoxelizeOptions voxelize_options();
  // The programs build() runs besides the voxelizer's (the empty-space bits).
  static std::vector<ProgramSpec> programs();

  // The lists of `mesh` (which must stay alive while they are used) on a grid fitted to mesh.bounds(),
  // `resolution` voxels along the longest side, on the device. While counts are deferred (a frame) nothing
  // waits; otherwise (a first frame, a test) the set-voxel total and the pair total are read at once. Throws
  // voxr::Error for a resolution outside 2..kSplitExtentVoxels (beyond it triangles would need splitting,
  // and split pieces are not the mesh's triangles), an empty mesh, or more than 2^32-1 (triangle, voxel)
  // pairs.
  void build(const DeviceMesh& mesh, uint32_t resolution);

  const DeviceVoxelGrid& grid() const { return grid_; }
  DeviceVoxelGrid& grid() { return grid_; }  // e.g. to read it back (read_back)
  const DeviceMesh& mesh() const;            // the mesh of the last build; InternalError before one
  // Device memory of the grid, its lists and the empty-space bits (not the mesh).
  uint64_t device_bytes() const { return grid_.device_bytes() + brick_words_ * 4; }
  // The kernel arguments of VOXR_TRIANGLE_GRID_PARAMS after build(). Throws InternalError before one.
  TriangleGridArgs view_args();

 private:
  ClRuntime& cl_;
  Voxelizer& voxelizer_;
  DeviceVoxelGrid grid_;
  const DeviceMesh* mesh_ = nullptr;
  GrowingBuffer bricks_;  // one bit per VOXR_BRICK^3 voxels: set where one is occupied
  glm::uvec3 brick_dims_{0};
  uint64_t brick_words_ = 0;
};

class TriangleGrids {
 public:
  TriangleGrids(ClRuntime& cl, Voxelizer& voxelizer);
  ~TriangleGrids();

  // Marks every grid stale (FrameRenderer, at the start of every try at a frame).
  void begin_frame();
  // The lists of `mesh` at `resolution`, built on the first call of the frame (TriangleGrid::build; again
  // for another mesh).
  TriangleGrid& get(const DeviceMesh& mesh, uint32_t resolution);
  // Device memory of every grid built so far.
  uint64_t device_bytes() const;

 private:
  struct Entry {
    std::unique_ptr<TriangleGrid> grid;
    bool fresh = false;  // built in this frame
  };
  ClRuntime& cl_;
  Voxelizer& voxelizer_;
  std::map<uint32_t, Entry> grids_;
};

}  // namespace voxr
