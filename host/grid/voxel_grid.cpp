#include "grid/voxel_grid.h"

#include <bit>

#include "util/error.h"

namespace voxr {

void expand_bits(std::span<const uint32_t> bits, uint64_t begin, uint64_t end, uint8_t* out) {
  for (uint64_t l = begin; l < end; ++l) *out++ = uint8_t((bits[l >> 5] >> (l & 31)) & 1u);
}

VoxelGrid solid_occupancy(const VoxelGrid& grid) {
  VoxelGrid out;
  out.spec = grid.spec;
  out.occ = grid.occ;
  for (size_t w = 0; w < grid.inside.size(); ++w) out.occ[w] |= grid.inside[w];
  for (uint32_t w : out.occ) out.voxels_set += uint64_t(std::popcount(w));
  return out;
}

}  // namespace voxr
