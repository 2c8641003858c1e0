// A voxel grid that stays on the device: what every voxelizer produces and what the effects read, frame
// after frame, with no host round trip. Reading it back into a host VoxelGrid (read_back) is a separate,
// explicit step used by file writers and tests.
//
// Layout (the channel table, host/grid/channel_table.h, says which channel is which):
//   occ, inside   dense bits, one 32-bit word per 32 voxels in linear order (x fastest), words() words.
//   ranked        the rank index (kernels/voxr_layout.h VOXR_RANKED): per occupancy word the word and the
//                 number of set voxels before it; words() 64-bit words. Present whenever a sparse channel
//                 is (build_rank_index otherwise).
//   count         voxels_set uint32, in rank order;
//   normal_sum    voxels_set x 3 int32 (fixed point, VOXR_NORMAL_ONE per writer), normal voxels_set x 3
//                 float (unit, zero where the sum cancels);
//   material      voxels_set uint32;
//   color         voxels_set uint32, RGBA8 (R in the low byte);
//   triangle lists (VoxelizeOptions::triangle_lists) list_offsets voxels_set + 1 uint64 (exclusive scan of
//                 count; the last entry is the total of pairs), list_ids list_capacity uint32: the mesh
//                 indices of the triangles of voxel r at [list_offsets[r], list_offsets[r + 1]), ascending.
// Why sparse by rank and not dense: a dense normal channel at 1024^3 needs 12 GiB; sparse it needs 12 bytes
// per surface voxel (tens of MiB), and a kernel pays one extra 8-byte load for the rank
// (bench/grid_view_bench.cpp measures the two against each other). Kernels read all of it through
// kernels/grid_view.h.
#pragma once

#include <cstdint>

#include "cl/cl_runtime.h"
#include "cl/scratch_buffers.h"
#include "core/grid_spec.h"
#include "grid/channel_table.h"
#include "grid/voxel_grid.h"
#include "voxr_layout.h"

namespace voxr {

class DeviceVoxelGrid;

// The arguments of a kernel's VOXR_GRID_VIEW_PARAMS (kernels/grid_view.h), for ClRuntime::launch.
struct GridViewArgs {
  VoxGridView view{};
  const cl::Buffer* occ = nullptr;
  const cl::Buffer* ranked = nullptr;
  const cl::Buffer* count = nullptr;
  const cl::Buffer* normal = nullptr;
  const cl::Buffer* material = nullptr;
  const cl::Buffer* inside = nullptr;
  void set_kernel_args(cl::Kernel& kernel, cl_uint& index) const;
};

class DeviceVoxelGrid {
 public:
  GridSpec spec;
  ChannelSet channels;          // the channels present
  uint64_t voxels_set = 0;      // set voxels: the length of every sparse channel (valid with the rank index;
                                // a frame with deferred counts: the capacity allocated, ranks past the true
                                // total unused)
  uint64_t inside_voxels = 0;   // set inside bits (when channels has inside)
  bool has_rank_index = false;  // whether `ranked` describes the current occupancy
  bool has_triangle_lists = false;  // list_offsets and list_ids describe the current voxels
  uint64_t list_capacity = 0;       // entries of list_ids (a frame with deferred counts: the capacity)
  // What the last voxelization into this grid counted, with headroom: the capacities the next one runs over
  // when a frame defers its counts (ClRuntime::counts_deferred). Kept per grid, not per voxelizer: one
  // voxelizer fills several grids a frame (the light's, the refraction grid), each with its own counts.
  struct DeferredCapacities {
    uint64_t listed = 0;   // hybrid: the large-triangle list
    uint64_t records = 0;  // the copy records (RecordBins::scan)
    uint64_t set = 0;      // the set voxels (the sparse channels' entries)
    uint64_t pairs = 0;    // the (triangle, voxel) pairs of the triangle lists
  } capacities;

  GrowingBuffer occ, inside, ranked;
  GrowingBuffer count, normal_sum, normal, material, color;
  GrowingBuffer list_offsets, list_ids;

  // Sparse storage (host/voxelize/sparse_voxelizer.h): occ holds brick_slots 8^3 bricks of 16 words each
  // (host/grid/sparse_voxel_grid.h's brick layout) instead of dense bits; the rank index and the sparse
  // channels follow that order. 0: dense.
  uint64_t brick_slots = 0;

  // 32-bit words of occ (dense bits on `spec`, or the brick slots' words) and of a dense inside channel.
  uint64_t words() const { return brick_slots ? brick_slots * 16 : (spec.voxel_count() + 31) / 32; }
  // Device memory the present channels use.
  uint64_t device_bytes() const;
  VoxGridView view() const;
  // view() and the channel buffers; absent channels get a 4-byte placeholder (never read: grid_view.h
  // checks the channel bits). Throws voxr::InternalError when a sparse channel lacks the rank index.
  GridViewArgs view_args(ClRuntime& cl);

  // Starts a new result on `grid` with `channels`: clears the flags and counts; buffers are kept for reuse
  // (an adopted occupancy array stays adopted).
  void reset(const GridSpec& grid, ChannelSet channels);

  // On a CPU device: the next voxelization writes its occupancy straight into `words` (zero, words() long
  // for the grid it runs on, aligned as ClRuntime::can_use_in_place needs, alive until release_adopted()),
  // so there is nothing to clear and nothing to copy back. Later voxelizations into the same array clear it
  // first.
  void adopt_occupancy(ClRuntime& cl, uint32_t* words, uint64_t count);
  // Drops the buffer over the adopted array (the caller keeps the array); nothing when none is adopted.
  void release_adopted();
  bool occupancy_adopted() const { return adopted_; }
  const uint32_t* adopted_words() const { return adopted_ ? adopted_words_ : nullptr; }
  // The occupancy buffer, ready for a voxelizer to set bits in: cleared, or the adopted (zero) host array.
  cl::Buffer& occupancy_for_writing(ClRuntime& cl);

 private:
  GrowingBuffer placeholder_;
  bool adopted_ = false;
  bool adopted_zero_ = false;  // the adopted array has not been written yet
  const uint32_t* adopted_words_ = nullptr;
};

// Builds the rank index from the occupancy (scan.cl) and sets voxels_set; nothing when it is current.
void build_rank_index(ClRuntime& cl, DeviceVoxelGrid& grid);
// Builds the rank index without waiting: the set-voxel total goes to `total` (a ulong on the device) and the
// caller sets voxels_set (the entries it allocates for the sparse channels).
void build_rank_index(ClRuntime& cl, DeviceVoxelGrid& grid, cl::Buffer& total);

// Every present channel copied into a host VoxelGrid. voxels_set comes from the rank index when there is
// one, else from the occupancy read back. An adopted occupancy array (adopted_occ, the one given to
// adopt_occupancy) is moved into the result instead of copied.
VoxelGrid read_back(ClRuntime& cl, DeviceVoxelGrid& grid, BitWords* adopted_occ = nullptr);

}  // namespace voxr
