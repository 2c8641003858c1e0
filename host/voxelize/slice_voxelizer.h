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

class SliceVoxelizer final : public SurfaceVoxelizer {
 public:
  // method: kHybrid, kSlice or kGrid.
  SliceVoxelizer(ClRuntime& cl, VoxelizeMethod method);

  std::vector<ProgramSpec> programs(const VoxelizeOptions& options) const override;
  void run(const DeviceMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options, DeviceVoxelGrid& out,
           VoxelizeStats& stats) override;

 private:
  ClRuntime& cl_;
  VoxelizeMethod method_;
  ScratchBuffers scratch_;  // device buffers kept between runs
  RecordBins copies_;       // the copy records of the slice path
};

}  // namespace voxr
