#include "io/grid_encoding.h"

#include "util/error.h"

namespace voxr {

void check_grid_layout(const VoxelGrid& grid) {
  VOXR_CHECK(grid.spec.voxel_count() > 0);
  const uint64_t words = (grid.spec.voxel_count() + 31) / 32;
  VOXR_CHECK_LE(words, uint64_t(grid.occ.size()));
  uint64_t set = 0;
  for (uint64_t w = 0; w < words; ++w) set += uint64_t(__builtin_popcount(grid.occ[w]));
  VOXR_CHECK_EQ(set, grid.voxels_set);
  if (const uint32_t tail = uint32_t(grid.spec.voxel_count() & 31); tail != 0)
    VOXR_CHECK_EQ(grid.occ[words - 1] >> tail, 0u);
  if (grid.channels.has(Channel::kCount)) VOXR_CHECK_EQ(uint64_t(grid.count.size()), grid.voxels_set);
  if (grid.channels.has(Channel::kMaterial)) VOXR_CHECK_EQ(uint64_t(grid.material.size()), grid.voxels_set);
  if (grid.channels.has(Channel::kColor)) VOXR_CHECK_EQ(uint64_t(grid.color.size()), grid.voxels_set);
  if (grid.channels.has(Channel::kNormal))
    VOXR_CHECK(grid.normal.size() == grid.voxels_set || grid.normal_sum.size() == grid.voxels_set);
}

void check_grid_layout(const SparseVoxelGrid& grid) {
  VOXR_CHECK(grid.spec.voxel_count() > 0);
  VOXR_CHECK(grid.brick_dims == brick_dims_of(grid.spec.dims));
  VOXR_CHECK_EQ(grid.brick_bits.size(), grid.bricks() * kBrickWords);
  VOXR_CHECK_EQ(grid.brick_rank.size(), grid.bricks() + 1);
  VOXR_CHECK_EQ(grid.brick_rank.back(), grid.voxels_set);
  VOXR_CHECK(!grid.channels.has(Channel::kInside));
  if (grid.channels.has(Channel::kColor)) VOXR_CHECK_EQ(uint64_t(grid.color.size()), grid.voxels_set);
  const uint64_t brick_count = uint64_t(grid.brick_dims.x) * grid.brick_dims.y * grid.brick_dims.z;
  for (size_t b = 0; b < grid.bricks(); ++b) {
    VOXR_CHECK_LT(grid.brick_index[b], brick_count);
    if (b > 0) VOXR_CHECK_LT(grid.brick_index[b - 1], grid.brick_index[b]);
    uint64_t set = 0;
    for (uint32_t w = 0; w < kBrickWords; ++w)
      set += uint64_t(std::popcount(grid.brick_bits[b * kBrickWords + w]));
    VOXR_CHECK_EQ(grid.brick_rank[b] + set, grid.brick_rank[b + 1]);
  }
  if (grid.channels.has(Channel::kCount)) VOXR_CHECK_EQ(uint64_t(grid.count.size()), grid.voxels_set);
  if (grid.channels.has(Channel::kMaterial)) VOXR_CHECK_EQ(uint64_t(grid.material.size()), grid.voxels_set);
  if (grid.channels.has(Channel::kNormal))
    VOXR_CHECK(grid.normal.size() == grid.voxels_set || grid.normal_sum.size() == grid.voxels_set);
}

std::pair<size_t, size_t> sparse_bricks_in_rows(const SparseVoxelGrid& grid, uint32_t z, uint32_t y0,
                                                uint32_t y1) {
  if (y0 >= y1) return {0, 0};
  const uint64_t layer = uint64_t(z / kBrickEdge) * grid.brick_dims.y;
  const uint64_t lo = (layer + y0 / kBrickEdge) * grid.brick_dims.x;
  const uint64_t hi = (layer + (y1 - 1) / kBrickEdge + 1) * grid.brick_dims.x;
  const auto first = std::lower_bound(grid.brick_index.begin(), grid.brick_index.end(), lo);
  const auto last = std::lower_bound(first, grid.brick_index.end(), hi);
  return {size_t(first - grid.brick_index.begin()), size_t(last - grid.brick_index.begin())};
}

// ---- NormalChannel ---------------------------------------------------------------------------------------

void NormalChannel::check(uint64_t voxels_set) const {
  VOXR_CHECK(!from_sum_ || normal_sum_.size() == voxels_set);
}

glm::vec3 NormalChannel::operator()(uint64_t rank) const {
  if (!from_sum_) return normal_[rank];
  const glm::vec3 sum(normal_sum_[rank]);
  const float len = glm::length(sum);
  return len > 0.0f ? sum / len : glm::vec3(0.0f);
}

}  // namespace voxr
