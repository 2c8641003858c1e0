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

// ---- NormalChannel ---------------------------------------------------------------------------------------

NormalChannel::NormalChannel(const VoxelGrid& grid)
    : grid_(grid), from_sum_(grid.normal.size() != grid.voxels_set) {
  VOXR_CHECK(!from_sum_ || grid.normal_sum.size() == grid.voxels_set);
}

glm::vec3 NormalChannel::operator()(uint64_t rank) const {
  if (!from_sum_) return grid_.normal[rank];
  const glm::vec3 sum(grid_.normal_sum[rank]);
  const float len = glm::length(sum);
  return len > 0.0f ? sum / len : glm::vec3(0.0f);
}

}  // namespace voxr
