#include "grid/device_voxel_grid.h"

#include <bit>

#include "cl/scan.h"

namespace voxr {

void GridViewArgs::set_kernel_args(cl::Kernel& kernel, cl_uint& index) const {
  kernel.setArg(index++, view);
  for (const cl::Buffer* b : {occ, ranked, count, normal, material, inside}) kernel.setArg(index++, *b);
}

uint64_t DeviceVoxelGrid::device_bytes() const {
  const uint64_t w = words();
  uint64_t bytes = w * 4;
  if (channels.has(Channel::kInside)) bytes += w * 4;
  if (has_rank_index) bytes += w * 8;
  if (channels.has(Channel::kCount)) bytes += voxels_set * 4;
  if (channels.has(Channel::kNormal)) bytes += voxels_set * 24;
  if (channels.has(Channel::kMaterial)) bytes += voxels_set * 4;
  if (channels.has(Channel::kColor)) bytes += voxels_set * 4;
  if (has_triangle_lists) bytes += (voxels_set + 1) * 8 + list_capacity * 4;
  return bytes;
}

VoxGridView DeviceVoxelGrid::view() const {
  VoxGridView v{};
  const std::array<float, 12> m = spec.world_to_grid();
  std::copy(m.begin(), m.end(), v.world_to_grid);
  for (int a = 0; a < 3; ++a) v.dims[a] = spec.dims[a];
  v.channels = channels.bits;
  v.voxels_set = uint32_t(voxels_set);
  v.has_rank_index = has_rank_index ? 1u : 0u;
  return v;
}

GridViewArgs DeviceVoxelGrid::view_args(ClRuntime& cl) {
  if (channels.sparse() && !has_rank_index)
    throw InternalError("view_args: the grid has sparse channels but no rank index");
  const cl::Buffer& none = placeholder_.ensure(cl, 4, "grid view placeholder");
  auto present = [&](Channel c, const GrowingBuffer& b) { return channels.has(c) ? &b.buffer : &none; };
  GridViewArgs args;
  args.view = view();
  args.occ = &occ.buffer;
  args.ranked = has_rank_index ? &ranked.buffer : &none;
  args.count = present(Channel::kCount, count);
  args.normal = present(Channel::kNormal, normal);
  args.material = present(Channel::kMaterial, material);
  args.inside = present(Channel::kInside, inside);
  return args;
}

void DeviceVoxelGrid::reset(const GridSpec& grid, ChannelSet set) {
  spec = grid;
  channels = set;
  voxels_set = 0;
  inside_voxels = 0;
  has_rank_index = false;
  has_triangle_lists = false;
  list_capacity = 0;
  brick_slots = 0;
}

void DeviceVoxelGrid::adopt_occupancy(ClRuntime& cl, uint32_t* words_data, uint64_t count) {
  occ.release();
  occ.buffer = cl.in_place_buffer(words_data, count * 4, "the occupancy bits");
  occ.bytes = count * 4;
  adopted_ = true;
  adopted_zero_ = true;
  adopted_words_ = words_data;
}

void DeviceVoxelGrid::release_adopted() {
  if (!adopted_) return;
  occ.release();
  adopted_ = false;
}

cl::Buffer& DeviceVoxelGrid::occupancy_for_writing(ClRuntime& cl) {
  const uint64_t bytes = words() * 4;
  if (adopted_) {
    VOXR_CHECK_LE(bytes, occ.bytes);
    if (!adopted_zero_) cl.fill_zero(occ.buffer, bytes, "clear");
    adopted_zero_ = false;
    return occ.buffer;
  }
  cl::Buffer& buffer = occ.ensure(cl, bytes, "the occupancy bits");
  cl.fill_zero(buffer, bytes, "clear");
  return buffer;
}

void build_rank_index(ClRuntime& cl, DeviceVoxelGrid& grid) {
  if (grid.has_rank_index) return;
  cl::Buffer total = cl.buffer(sizeof(cl_ulong), "the set-voxel total");
  build_rank_index(cl, grid, total);
  cl_ulong set = 0;
  cl.download(total, &set, sizeof(set), "readback rank total");
  grid.voxels_set = set;
}

void build_rank_index(ClRuntime& cl, DeviceVoxelGrid& grid, cl::Buffer& total) {
  const uint64_t words = grid.words();
  cl::Buffer& ranked = grid.ranked.ensure(cl, words * 8, "the rank index");
  exclusive_scan(cl, ScanKind::kRankedWords, grid.occ.buffer, ranked, words, total, "rank");
  grid.has_rank_index = true;
}

VoxelGrid read_back(ClRuntime& cl, DeviceVoxelGrid& grid, BitWords* adopted_occ) {
  VoxelGrid out;
  out.spec = grid.spec;
  out.channels = grid.channels;
  const uint64_t words = grid.words();
  if (grid.occupancy_adopted()) {
    VOXR_CHECK(adopted_occ && adopted_occ->data() == grid.adopted_words() && adopted_occ->size() == words);
    cl.sync_to_host(grid.occ.buffer, words * 4, "readback occupancy");
    out.occ = std::move(*adopted_occ);
  } else {
    out.occ.resize(words);
    cl.download(grid.occ.buffer, out.occ.data(), words * 4, "readback occupancy");
  }
  if (grid.channels.has(Channel::kInside)) {
    out.inside.resize(words);
    cl.download(grid.inside.buffer, out.inside.data(), words * 4, "readback inside");
    out.inside_voxels = grid.inside_voxels;
  }
  const uint64_t n = grid.voxels_set;
  if (grid.channels.has(Channel::kCount)) {
    out.count.resize(n);
    cl.download(grid.count.buffer, out.count.data(), n * 4, "readback count");
  }
  if (grid.channels.has(Channel::kNormal)) {
    out.normal_sum.resize(n);
    out.normal.resize(n);
    cl.download(grid.normal_sum.buffer, out.normal_sum.data(), n * 12, "readback normal sums");
    cl.download(grid.normal.buffer, out.normal.data(), n * 12, "readback normals");
  }
  if (grid.channels.has(Channel::kMaterial)) {
    out.material.resize(n);
    cl.download(grid.material.buffer, out.material.data(), n * 4, "readback material");
  }
  if (grid.channels.has(Channel::kColor)) {
    out.color.resize(n);
    cl.download(grid.color.buffer, out.color.data(), n * 4, "readback color");
  }
  cl.finish("reading the grid back");
  if (grid.has_rank_index) {
    out.voxels_set = n;
  } else {
    for (uint32_t w : out.occ) out.voxels_set += uint64_t(std::popcount(w));
  }
  return out;
}

}  // namespace voxr
