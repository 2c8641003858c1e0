// Voxelization into 8^3 bricks (host/grid/sparse_voxel_grid.h) for grids whose dense bits outgrow the
// device or the host (4096^3 is 8 GiB of bits, 16384^3 is 512 GiB): device and host memory grow with the
// surface, not with the grid's volume, and a grid larger than the memory budget is done in slabs of brick
// layers, one after the other, on one upload of the mesh.
//
// Per slab (as many brick layers as the budget allows):
//   1. coarse pass: the slice voxelizer (hybrid, conservative) on the grid of bricks — one voxel per 8^3
//      brick, same corner and axes — with the margin widened by the fine grid's snap bound, so every brick in
//      which the fine rule can set a voxel is marked (a superset; see sparse_voxelizer.cpp for the bound);
//   2. the rank index of the brick bits: each marked brick's slot (cl/scan.h);
//   3. fine pass: the user's method and rule over the slab's slices (SliceWindow: an exact integer shift of
//      the snapped z, the whole grid's margin), each voxel written into its brick's slot
//      (kernels/voxelize/vox_scanline.h VOX_SPARSE), then the attribute passes over the slots' rank index;
//   4. read back: the slab's bricks and channels, marked bricks that stayed empty dropped.
// The result is bit for bit the dense voxelization's (tests/sparse_voxelizer_test.cpp), in brick order.
// Slice family only (hybrid, slice, grid); no solid fill and no triangle lists (they need dense grids).
#pragma once

#include <cstdint>
#include <memory>

#include "cl/cl_runtime.h"
#include "core/grid_spec.h"
#include "core/triangle_soup.h"
#include "grid/device_voxel_grid.h"
#include "grid/sparse_voxel_grid.h"
#include "voxelize/voxelizer.h"

namespace voxr {

class SliceVoxelizer;

// Counts of a sparse run, beside VoxelizeStats.
struct SparseStats {
  uint64_t slabs = 0;
  uint64_t bricks_marked = 0;      // by the coarse pass
  uint64_t bricks_kept = 0;        // holding at least one set voxel
  uint64_t peak_device_bytes = 0;  // the largest slab's buffers: grid (below) and the passes' scratch
  uint64_t peak_grid_bytes = 0;  // the largest slab's grid: brick table, slots and their rank index, channels
  uint64_t memory_budget = 0;    // the budget the slabs were sized by
};

// The device memory a sparse run may use when the user gives no budget: a quarter of the device's memory,
// and no more than twice its largest allocation.
uint64_t default_memory_budget(const ClRuntime& cl);

// Dense bytes of the occupancy bits of `dims` (what --layout dense allocates on the device and the host).
inline uint64_t dense_occupancy_bytes(const glm::uvec3& dims) {
  return (uint64_t(dims.x) * dims.y * dims.z + 31) / 32 * 4;
}

class SparseVoxelizer {
 public:
  explicit SparseVoxelizer(ClRuntime& cl);
  ~SparseVoxelizer();

  // Throws voxr::Error for what the sparse layout cannot produce (slicemap, solid, triangle lists), naming
  // the option.
  static void validate(const VoxelizeOptions& options);
  // Builds the coarse and fine programs.
  void prepare(const VoxelizeOptions& options);

  // Voxelizes `soup` on `grid` into bricks under `memory_budget` device bytes per slab (0: the default).
  // `bounds` (optional) must contain the soup's vertices. Throws voxr::Error when one brick layer of the
  // grid does not fit the budget, or validate's errors.
  SparseVoxelGrid run(const TriangleSoup& soup, const GridSpec& grid, const VoxelizeOptions& options,
                      uint64_t memory_budget = 0, VoxelizeStats* stats = nullptr,
                      SparseStats* sparse_stats = nullptr, const Bounds* bounds = nullptr);

 private:
  ClRuntime& cl_;
  std::unique_ptr<SliceVoxelizer> coarse_;
  std::unique_ptr<SliceVoxelizer> fine_;
  VoxelizeMethod fine_method_ = VoxelizeMethod::kHybrid;
  DeviceVoxelGrid brick_grid_, slots_;  // kept for buffer reuse between slabs and runs
};

}  // namespace voxr
