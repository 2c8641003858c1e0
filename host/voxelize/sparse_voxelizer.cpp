#include "voxelize/sparse_voxelizer.h"

#include <algorithm>
#include <bit>

#include <fmt/format.h>

#include "util/clock.h"
#include "voxelize/device_colors.h"
#include "voxelize/device_mesh.h"
#include "voxelize/slice_voxelizer.h"
#include "voxelize/snapped_triangle.h"

namespace voxr {

namespace {

// Device bytes per brick layer of the brick table: one bit per brick and its rank index (8 bytes per 32).
uint64_t table_bytes_per_layer(const glm::uvec3& bricks) {
  const uint64_t layer = uint64_t(bricks.x) * bricks.y;
  return layer / 8 + layer / 4 + 16;
}

// Device bytes per marked brick of the fine pass: 16 words of bits and, with sparse channels, their rank
// index (16 x 8 bytes) and the channels of the brick's set voxels (planned at 128 of 512: a surface
// crossing a brick; a brick of a fuller surface costs more, and a failed allocation says so).
uint64_t slot_bytes(const VoxelizeOptions& options) {
  uint64_t bytes = 64;
  if (!options.channels.sparse()) return bytes;
  uint64_t per_voxel = 16;  // the packed count/normal accumulators or the rank total's share
  if (options.channels.has(Channel::kCount)) per_voxel += 4;
  if (options.channels.has(Channel::kNormal)) per_voxel += 24;
  if (options.channels.has(Channel::kMaterial)) per_voxel += 4;
  if (options.channels.has(Channel::kColor)) per_voxel += 20;  // the colour sums and the RGBA8 channel
  return bytes + 128 + 128 * per_voxel;
}

}  // namespace

uint64_t default_memory_budget(const ClRuntime& cl) {
  const DeviceInfo& device = cl.device();
  return std::min(device.global_memory / 4, 2 * device.max_allocation);
}

SparseVoxelizer::SparseVoxelizer(ClRuntime& cl)
    : cl_(cl), coarse_(std::make_unique<SliceVoxelizer>(cl, VoxelizeMethod::kHybrid)) {}

SparseVoxelizer::~SparseVoxelizer() = default;

void SparseVoxelizer::validate(const VoxelizeOptions& options) {
  options.validate();
  if (options.method == VoxelizeMethod::kSlicemap)
    fail("--layout sparse voxelizes with the slice family (hybrid, slice, grid), not --method slicemap");
  if (options.solid) fail("--solid fills dense grids only: use --layout dense (or a lower --res)");
  if (options.triangle_lists) fail("triangle lists are built on dense grids only");
}

void SparseVoxelizer::prepare(const VoxelizeOptions& options) {
  validate(options);
  if (!fine_ || fine_method_ != options.method) {
    fine_ = std::make_unique<SliceVoxelizer>(cl_, options.method);
    fine_method_ = options.method;
  }
  cl_.build_programs(coarse_->programs(conservative_occupancy_options()));
  cl_.build_programs(fine_->sparse_programs(options));
}

SparseVoxelGrid SparseVoxelizer::run(const TriangleSoup& soup, const GridSpec& grid,
                                     const VoxelizeOptions& options, uint64_t memory_budget,
                                     VoxelizeStats* stats, SparseStats* sparse_stats, const Bounds* bounds) {
  const auto start = Clock::now();
  prepare(options);
  auto progress = [&](const std::string& stage) {
    if (options.progress) options.progress(stage);
  };
  const uint64_t budget = memory_budget ? memory_budget : default_memory_budget(cl_);
  progress("upload");
  DeviceMesh mesh = upload_mesh(cl_, soup, grid, SplitCull::kGrid, bounds);
  if (options.channels.has(Channel::kColor) && !soup.colors.empty())
    mesh.attach_colors(std::make_shared<const DeviceColors>(cl_, mesh.soup_for_colors(soup), "the mesh"));
  cl_.finish();
  const auto profile_start = cl_.profiler().stats();

  SparseVoxelGrid result;
  result.spec = grid;
  result.channels = options.channels;
  result.brick_dims = brick_dims_of(grid.dims);
  result.brick_rank.push_back(0);
  const glm::uvec3 bricks = result.brick_dims;
  const uint64_t layer = uint64_t(bricks.x) * bricks.y;

  // The grid of bricks: one voxel per 8^3 brick, the same corner and axes.
  GridSpec coarse = grid;
  coarse.voxel_size = grid.voxel_size * float(kBrickEdge);
  coarse.dims = bricks;
  // The coarse margin. The fine rule sets a voxel only where the fine-snapped triangle meets the voxel's
  // box widened by the fine margin m_f (1/256 voxel units; 0 for the centre rule, whose set is inside the
  // conservative one); the fine-snapped vertices lie within m_f of the exact ones, the coarse-snapped within
  // the coarse snap bound m_c (1/256 brick units). So the coarse-snapped triangle meets the brick's box
  // widened by m_c + 2 m_f / 8 coarse units, which the coarse conservative rule tests: every brick holding a
  // set voxel is marked.
  const uint32_t fine_margin = snap_margin(grid, mesh.bounds());
  const uint32_t extra_margin = (2 * fine_margin + kBrickEdge - 1) / kBrickEdge + 1;

  const uint64_t per_layer = table_bytes_per_layer(bricks);
  const uint64_t per_slot = slot_bytes(options);
  uint64_t slab_layers = std::max<uint64_t>(1, (budget / 4) / per_layer);
  // The brick table's rank index (8 bytes per 32 bricks) is its largest buffer.
  slab_layers = std::min<uint64_t>(slab_layers, cl_.device().max_allocation / (layer / 4 + 1));
  slab_layers = std::clamp<uint64_t>(slab_layers, 1, bricks.z);
  if (per_layer > budget)
    fail("one layer of {} x {} bricks needs {} MiB of device memory, more than the {} of {} MiB", bricks.x,
         bricks.y, per_layer >> 20, memory_budget ? "--memory-budget" : "device's default budget",
         budget >> 20);

  VoxelizeStats local;
  // Triangles the slabs' fine passes gave to the slice path (a triangle in two slabs counts twice).
  uint64_t sliced = 0;
  SparseStats sparse;
  sparse.memory_budget = budget;
  std::vector<uint32_t> brick_bits_host;
  uint32_t first_layer = 0;
  while (first_layer < bricks.z) {
    const uint32_t layers = uint32_t(std::min<uint64_t>(slab_layers, bricks.z - first_layer));
    progress(fmt::format("slab {}/{} (brick layers {}..{} of {})", sparse.slabs + 1,
                         sparse.slabs + (bricks.z - first_layer + layers - 1) / layers, first_layer,
                         first_layer + layers - 1, bricks.z));
    // 1. coarse pass: the bricks of the slab's layers.
    GridSpec coarse_window = coarse;
    coarse_window.dims.z = layers;
    brick_grid_.reset(coarse_window, ChannelSet{});
    const uint64_t table_words = brick_grid_.words();
    brick_grid_.ranked.ensure(cl_, (table_words + 1) * 8, "the brick table");
    VoxelizeStats coarse_stats;
    coarse_->run(mesh, coarse, conservative_occupancy_options(),
                 SliceWindow{first_layer, layers, extra_margin, nullptr}, brick_grid_, coarse_stats);
    // 2. the slots: the rank index of the brick bits, and the flag a kernel sets for a voxel outside them.
    build_rank_index(cl_, brick_grid_);
    const uint64_t slots = brick_grid_.voxels_set;
    const uint64_t table_bytes = (table_words + 1) * 8;
    const uint64_t slab_bytes = table_bytes + slots * per_slot;
    // Halve the slab when its buffers pass the budget, one of them the device's largest allocation (the
    // slots' bits; with channels their rank index and the packed sums of the planned 128 voxels per brick),
    // or its planned voxels the 2^32 ranks of the attribute channels.
    const uint64_t largest = options.channels.sparse() ? slots * 128 * 16 : slots * 64;
    const bool too_many_ranks = options.channels.sparse() && slots * 128 >= (uint64_t(1) << 32);
    if ((slab_bytes > budget || largest > cl_.device().max_allocation || too_many_ranks) && layers > 1) {
      slab_layers = std::max<uint32_t>(1, layers / 2);  // too many bricks for one slab: halve and redo
      continue;
    }
    cl_.queue().enqueueFillBuffer(brick_grid_.ranked.buffer, cl_ulong(0), table_words * 8, 8);
    sparse.bricks_marked += slots;
    // The rank index holds the brick bits too (VOXR_RANKED): the host reads the bits now and the device
    // drops them before the slots are allocated, so the fine pass holds the table once.
    brick_bits_host.resize(table_words);
    cl_.download(brick_grid_.occ.buffer, brick_bits_host.data(), table_words * 4, "readback brick bits");
    brick_grid_.occ.release();

    // 3. fine pass into the slots.
    const uint32_t first_slice = first_layer * kBrickEdge;
    const uint32_t slices = std::min(grid.dims.z, (first_layer + layers) * kBrickEdge) - first_slice;
    GridSpec fine_window = grid;
    fine_window.dims.z = slices;
    slots_.reset(fine_window, options.channels);
    slots_.brick_slots = slots;
    VoxelGrid part;
    if (slots > 0) {
      VoxelizeStats fine_stats;
      fine_->run(mesh, grid, options.surface_only(),
                 SliceWindow{first_slice, slices, 0, &brick_grid_.ranked.buffer}, slots_, fine_stats);
      local.triangles = fine_stats.triangles;
      sliced += fine_stats.triangles - fine_stats.direct_triangles;
      local.copies += fine_stats.copies;
      local.work_items += fine_stats.work_items;
      local.batches += fine_stats.batches;
      local.margin = fine_stats.margin;
      const uint64_t grid_bytes = table_bytes + slots_.device_bytes();
      sparse.peak_grid_bytes = std::max(sparse.peak_grid_bytes, grid_bytes);
      // The coarse pass held the brick bits beside the table; the fine pass holds the slots instead.
      const uint64_t coarse_phase = table_words * 4 + table_bytes;
      sparse.peak_device_bytes =
          std::max(sparse.peak_device_bytes,
                   std::max(grid_bytes, coarse_phase) + fine_stats.device_bytes + coarse_stats.device_bytes);
      // 4. read back: the slab's brick bits, its slots and channels.
      progress("readback");
      cl_ulong missing = 0;
      cl_.download(brick_grid_.ranked.buffer, &missing, 8, "readback brick flag", table_words * 8);
      if (missing)
        throw InternalError(
            "a voxel fell outside the bricks the coarse pass marked (the coarse margin is short)");
      part = read_back(cl_, slots_);
    }
    // Marked bricks in slot order are the set brick bits in linear order; keep those with a set voxel.
    uint64_t slot = 0;
    const uint64_t base = uint64_t(first_layer) * layer;
    for (uint64_t w = 0; w < brick_bits_host.size() && slot < slots; ++w)
      for (uint32_t word = brick_bits_host[w]; word; word &= word - 1, ++slot) {
        const uint32_t* bits = part.occ.data() + slot * kBrickWords;
        uint64_t set = 0;
        for (uint32_t i = 0; i < kBrickWords; ++i) set += uint64_t(std::popcount(bits[i]));
        if (set == 0) continue;
        result.brick_index.push_back(base + w * 32 + uint64_t(std::countr_zero(word)));
        result.brick_bits.insert(result.brick_bits.end(), bits, bits + kBrickWords);
        result.brick_rank.push_back(result.brick_rank.back() + set);
      }
    VOXR_CHECK_EQ(result.brick_rank.back() - result.voxels_set, part.voxels_set);
    result.voxels_set = result.brick_rank.back();
    auto append = [](auto& to, auto& from) { to.insert(to.end(), from.begin(), from.end()); };
    append(result.count, part.count);
    append(result.normal_sum, part.normal_sum);
    append(result.normal, part.normal);
    append(result.material, part.material);
    append(result.color, part.color);
    brick_bits_host.clear();
    ++sparse.slabs;
    first_layer += layers;
  }
  sparse.bricks_kept = result.bricks();

  const Profiler::Split split = cl_.profiler().since(profile_start);
  // One slab: the triangles the direct pass took; several: those no slab gave to the slice path, at least.
  local.direct_triangles = local.triangles - std::min(local.triangles, sliced);
  local.voxels_set = result.voxels_set;
  local.triangles_split = mesh.triangles_split();
  local.device_bytes = sparse.peak_device_bytes;
  local.upload_ms = mesh.upload_ms();
  local.kernels_ms = split.kernels_ms;
  local.stage_ms = split.stage_ms;
  local.readback_ms = split.readback_ms;
  local.wall_ms = ms_since(start);
  if (stats) *stats = local;
  if (sparse_stats) *sparse_stats = sparse;
  return result;
}

}  // namespace voxr
