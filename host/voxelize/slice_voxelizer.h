// The papers' one-pass slice voxelization as OpenCL kernels:
//   vox_setup (per triangle: snap, slab and row range, copy count) -> scan (offsets) ->
//   vox_expand (one record per copy: the geometry shader's duplication) -> vox_raster (clip the copy to its
//   slab, walk its rows, set voxels) -> [attributes: rank scan of the occupancy words -> vox_raster pass 2
//   -> vox_finalize (unit normals)].
// Copies beyond the memory budget are expanded and rasterized in batches.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include "cl/cl_runtime.h"
#include "cl/scratch_buffers.h"
#include "core/grid_spec.h"
#include "core/triangle_soup.h"
#include "voxelize/raster_mode.h"
#include "voxelize/voxel_grid.h"

namespace voxr {

// How triangles reach the slabs: the papers' one-pass duplication (one record per copy), or the "Grid"
// baseline of their Table 1 (Llamas 2007): one pass per slab over every triangle. Same voxels either way.
enum class VoxelizeMethod { kSlice, kGrid };

struct VoxelizeOptions {
  VoxelizeMethod method = VoxelizeMethod::kSlice;
  RasterMode mode = RasterMode::kConservative;
  ChannelSet channels;
  uint32_t rows_per_copy = 4;                              // rows of a slab one raster work item walks
  uint64_t copy_budget_bytes = 256ull << 20;               // device memory for copy records per batch
  std::function<void(const std::string& stage)> progress;  // optional, called between stages
};

struct VoxelizeStats {
  uint64_t triangles = 0;        // uploaded (after splitting oversized triangles)
  uint64_t triangles_split = 0;  // input triangles that were split
  uint64_t copies = 0;           // (triangle, slab, row block) records; 0 for the Grid baseline
  uint64_t work_items = 0;       // raster work items: copies, or triangles x slabs for Grid
  uint64_t batches = 0;
  uint64_t voxels_set = 0;
  uint64_t device_bytes = 0;  // device memory the run's buffers need
  double upload_ms = 0.0;     // from profiling events
  double kernels_ms = 0.0;
  double readback_ms = 0.0;
  double wall_ms = 0.0;                    // host clock around the whole run, including waits
  std::map<std::string, double> stage_ms;  // per kernel stage
  double total_ms() const { return upload_ms + kernels_ms + readback_ms; }
  // Sets the profiled times from `split` and the wall time since `start`.
  void record_times(const Profiler::Split& split, std::chrono::steady_clock::time_point start);
};

// Triangles uploaded once, voxelized any number of times (benchmarks time the kernels alone).
class DeviceMesh {
 public:
  DeviceMesh(ClRuntime& cl, const TriangleSoup& soup);
  uint32_t triangle_count() const { return triangle_count_; }
  const cl::Buffer& positions() const { return positions_; }
  const cl::Buffer& triangles() const { return triangles_; }

 private:
  cl::Buffer positions_;
  cl::Buffer triangles_;
  uint32_t triangle_count_ = 0;
};

// Splits oversized triangles (triangle_splitter.h), uploads the soup and runs `voxelize` on it; `stats`
// (optional) then also holds the split count, the upload time and the wall time of the whole.
VoxelGrid upload_and_voxelize(ClRuntime& cl, const TriangleSoup& soup, const GridSpec& grid,
                              VoxelizeStats* stats,
                              const std::function<VoxelGrid(const DeviceMesh&)>& voxelize);

class SliceVoxelizer {
 public:
  explicit SliceVoxelizer(ClRuntime& cl) : cl_(cl), scratch_(cl) {}

  // Uploads, voxelizes and reads back; stats (optional) receive counts and profiled times.
  VoxelGrid run(const TriangleSoup& soup, const GridSpec& grid, const VoxelizeOptions& options,
                VoxelizeStats* stats = nullptr);
  // Voxelizes an uploaded mesh and reads back. The mesh must not need splitting (see
  // split_oversized_triangles).
  VoxelGrid run(const DeviceMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options,
                VoxelizeStats* stats = nullptr);

 private:
  ClRuntime& cl_;
  ScratchBuffers scratch_;  // device buffers kept between runs
};

}  // namespace voxr
