// Eisemann & Decoret 2006, "Fast Scene Voxelization and Applications": the slicemap baseline. Binary
// (occupancy only); every triangle is rasterized once in 2D and each fragment sets one bit of its column.
//
// Exact semantics (all integers on the snapped vertices of kernels/common/vox_triangle.h, S = VOXR_SUBVOXEL =
// 256, B = dims.z, Z = B * S):
//   column (i, j)  one per i < dims.x, j < dims.y; its slicemap is B bits, ceil(B / 32) uint words.
//   fragment       triangle t covers the column centre ((i + 1/2) S, (j + 1/2) S) of its projection on the
//                  slicing plane under the top-left tie rule (exactly the centre mode of vox_scanline.h; a
//                  triangle edge-on to z covers nothing). Its depth is zf = floor(S * z), z the exact depth
//                  (voxels) of t's plane at the centre. Fragments with zf outside [0, Z) are outside the grid
//                  and dropped everywhere (depth range and bits).
//   uniform        bit(zf) = floor(zf / S): the voxel slab [k, k+1) holding the depth. Bit b is voxel b, so
//                  the uniform grid equals SliceVoxelizer's centre mode exactly.
//   local          (scene-fitted) per column near = min zf, far = max zf over its fragments (depth pre-pass),
//                  W = far - near + 1, and bit(zf) = floor((zf - near) * B / W). Bit b holds the fixed-point
//                  depths zf in [near + ceil(b W / B), near + ceil((b + 1) W / B)) (empty for some b when
//                  W < B). Since W <= Z, a bit is never wider than one voxel, so it meets one or two voxels.
//   voxels         voxel (i, j, k) is set iff some set bit b of column (i, j) holds a depth in [k S, (k+1)
//   S):
//                  uniform: bit k set; local: a set bit in [bit(max(k S, near)), bit(min((k+1) S - 1, far))].
//                  Hence local's grid contains uniform's (a fragment's bit always holds its own voxel) plus
//                  the neighbour voxel of every bit that straddles a voxel face.
//   Steep triangles leave holes (one fragment per column): that is the method's failure being measured.
//
// Stages: slicemap_setup (snap, count tiles of the projected bounding box) -> scan -> expand_copies (one
// record per (triangle, tile); cl/record_bins.h) -> [local: slicemap_raster depth pass, per column atomic
// near/far] -> slicemap_raster bits pass (atomic_or one bit per fragment) -> slicemap_voxels (bits ->
// occupancy).
#pragma once

#include <cstdint>
#include <vector>

#include "cl/record_bins.h"
#include "cl/scratch_buffers.h"
#include "voxelize/slicemap_slicing.h"
#include "voxelize/voxelizer.h"

namespace voxr {

// The raw slicemap as the kernels leave it (for tests and analysis; the voxelizer converts it to voxels).
struct Slicemap {
  GridSpec spec;
  SlicemapSlicing slicing = SlicemapSlicing::kUniform;
  uint32_t words_per_column = 0;  // ceil(dims.z / 32)
  // Column (i, j) is words [(j * dims.x + i) * words_per_column, +words_per_column); bit b is bit b % 32 of
  // word b / 32.
  std::vector<uint32_t> bits;
  // Local slicing only (empty for uniform): fixed-point depth range of each column's fragments, indexed
  // j * dims.x + i; a column without fragments has near = kEmptyNear > far = 0.
  std::vector<uint32_t> near, far;
  static constexpr uint32_t kEmptyNear = 0xffffffffu;

  uint64_t column(uint32_t i, uint32_t j) const { return uint64_t(j) * spec.dims.x + i; }
  bool bit(uint32_t i, uint32_t j, uint32_t b) const {
    return (bits[column(i, j) * words_per_column + b / 32] >> (b % 32)) & 1u;
  }
  uint32_t bits_set(uint32_t i, uint32_t j) const;  // set bits of one column
  uint64_t bits_set() const;                        // all columns
};

class SlicemapVoxelizer final : public SurfaceVoxelizer {
 public:
  explicit SlicemapVoxelizer(ClRuntime& cl) : cl_(cl), scratch_(cl) {}

  std::vector<ProgramSpec> programs(const VoxelizeOptions& options) const override;
  // occ only. stats: copies = (triangle, tile) raster records, batches, work items.
  void run(const DeviceMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options, DeviceVoxelGrid& out,
           VoxelizeStats& stats) override;

  // The raw bits (and local depth ranges) of the last run.
  Slicemap read_slicemap();

 private:
  ClRuntime& cl_;
  ScratchBuffers scratch_;  // device buffers kept between runs
  RecordBins tiles_;        // the (triangle, tile) raster records
  GridSpec last_grid_;
  SlicemapSlicing last_slicing_ = SlicemapSlicing::kUniform;
};

}  // namespace voxr
