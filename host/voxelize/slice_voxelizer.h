// The slice family of surface methods (voxelizer.h): hybrid, slice and grid, sharing the scanline code
// (kernels/voxelize/vox_scanline.h) and thus producing identical voxels.
//   hybrid: vox_direct (small triangles, one work item each; the large ones listed) -> vox_setup over the
//           list -> scan -> expand_copies -> vox_raster
//   slice:  vox_setup (every triangle: snap, slab and row range, copy count) -> scan (offsets) ->
//           expand_copies (one record per copy: the geometry shader's duplication; cl/record_bins.h) ->
//           vox_raster (clip the copy to its slab, walk its rows, set voxels)
//   grid:   vox_setup (snap only) -> one vox_grid launch per slab over every triangle
// then, for count/normal/material: the rank index (scan.cl) -> the same passes again adding attributes at
// each voxel's rank -> vox_finalize (unpack, unit normals). Copies beyond the record budget are expanded
// and rasterized in batches.
#pragma once

#include "cl/record_bins.h"
#include "cl/scratch_buffers.h"
#include "voxelize/voxelizer.h"

namespace voxr {

// A part of a run (the sparse voxelizer's passes, host/voxelize/sparse_voxelizer.h): the slices [first_slice,
// first_slice + slices) of the grid, written into an `out` whose spec is the window's (GridSpec of `slices`
// slices) — dense bits, or with `bricks` into out.brick_slots 8^3 brick slots (kernels/voxelize/
// vox_scanline.h VOX_SPARSE). Voxels are bit for bit those of the same slices of a whole-grid run: the
// snapped z is shifted by an exact integer and the conservative margin is the whole grid's.
struct SliceWindow {
  uint32_t first_slice = 0;
  uint32_t slices = 0;                 // 0: the whole grid
  uint32_t extra_margin = 0;           // conservative rule: added to the snap margin (1/VOXR_SUBVOXEL units)
  const cl::Buffer* bricks = nullptr;  // the brick table: the rank index of the window's brick occupancy
                                       // (one bit per brick, linear brick order), then one flag word
};

class SliceVoxelizer final : public SurfaceVoxelizer {
 public:
  // method: kHybrid, kSlice or kGrid.
  SliceVoxelizer(ClRuntime& cl, VoxelizeMethod method);

  std::vector<ProgramSpec> programs(const VoxelizeOptions& options) const override;
  void run(const DeviceMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options, DeviceVoxelGrid& out,
           VoxelizeStats& stats) override;
  // run() over a window of `grid` (above).
  void run(const DeviceMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options,
           const SliceWindow& window, DeviceVoxelGrid& out, VoxelizeStats& stats);
  // The programs of a run into bricks (VOX_SPARSE).
  std::vector<ProgramSpec> sparse_programs(const VoxelizeOptions& options) const;

 private:
  std::vector<ProgramSpec> programs_of(const VoxelizeOptions& options, bool sparse) const;

  ClRuntime& cl_;
  VoxelizeMethod method_;
  ScratchBuffers scratch_;  // device buffers kept between runs
  RecordBins copies_;       // the copy records of the slice path
};

}  // namespace voxr
