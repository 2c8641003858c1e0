#include "grid/sparse_voxel_grid.h"

#include <algorithm>
#include <limits>

#include "util/error.h"

namespace voxr {

uint64_t SparseVoxelGrid::memory_bytes() const {
  return brick_index.size() * sizeof(uint64_t) + brick_bits.size() * sizeof(uint32_t) +
         brick_rank.size() * sizeof(uint64_t) + count.size() * sizeof(uint32_t) +
         normal_sum.size() * sizeof(glm::ivec3) + normal.size() * sizeof(glm::vec3) +
         material.size() * sizeof(uint32_t) + color.size() * sizeof(uint32_t);
}

bool SparseVoxelGrid::occupied(uint32_t i, uint32_t j, uint32_t k) const {
  if (i >= spec.dims.x || j >= spec.dims.y || k >= spec.dims.z) return false;
  const uint64_t key =
      (uint64_t(k / kBrickEdge) * brick_dims.y + j / kBrickEdge) * brick_dims.x + i / kBrickEdge;
  const auto it = std::lower_bound(brick_index.begin(), brick_index.end(), key);
  if (it == brick_index.end() || *it != key) return false;
  const uint32_t b = (i & 7u) + 8u * ((j & 7u) + 8u * (k & 7u));
  return (brick_bits[size_t(it - brick_index.begin()) * kBrickWords + b / 32] >> (b % 32)) & 1u;
}

SparseVoxelGrid to_sparse(const VoxelGrid& dense) {
  SparseVoxelGrid out;
  out.spec = dense.spec;
  out.channels = dense.channels;
  out.channels.remove(Channel::kInside);
  out.brick_dims = brick_dims_of(dense.spec.dims);
  const glm::uvec3 d = dense.spec.dims, bd = out.brick_dims;
  const bool has_count = !dense.count.empty(), has_sum = !dense.normal_sum.empty(),
             has_normal = !dense.normal.empty(), has_material = !dense.material.empty(),
             has_color = !dense.color.empty();
  const bool any_channel = has_count || has_sum || has_normal || has_material || has_color;

  // One layer of bricks (8 voxel slices) at a time: its bits, and for each of its voxels the dense rank.
  const size_t layer_bricks = size_t(bd.x) * bd.y;
  std::vector<uint32_t> bits(layer_bricks * kBrickWords);
  std::vector<uint64_t> dense_rank(any_channel ? layer_bricks * kBrickVoxels : 0);
  uint64_t rank = 0;  // dense rank of the next set voxel in linear order
  out.brick_rank.push_back(0);
  for (uint32_t bz = 0; bz < bd.z; ++bz) {
    std::fill(bits.begin(), bits.end(), 0u);
    const uint32_t z1 = std::min(d.z, (bz + 1) * kBrickEdge);
    for (uint32_t z = bz * kBrickEdge; z < z1; ++z)
      for (uint32_t y = 0; y < d.y; ++y) {
        const uint64_t begin = dense.spec.linear_index(0, y, z), end = begin + d.x;
        for (uint64_t w = begin >> 5; w <= (end - 1) >> 5; ++w) {
          uint32_t word = dense.occ[w];
          if (w == begin >> 5) word &= ~0u << (begin & 31);
          if (w == (end - 1) >> 5 && ((end - 1) & 31) != 31) word &= (2u << ((end - 1) & 31)) - 1u;
          while (word) {
            const uint32_t x = uint32_t(w * 32 + uint32_t(std::countr_zero(word)) - begin);
            const size_t brick = size_t(y / kBrickEdge) * bd.x + x / kBrickEdge;
            const uint32_t b = (x & 7u) + 8u * ((y & 7u) + 8u * (z & 7u));
            bits[brick * kBrickWords + b / 32] |= 1u << (b % 32);
            if (any_channel) dense_rank[brick * kBrickVoxels + b] = rank;
            ++rank;
            word &= word - 1;
          }
        }
      }
    for (size_t brick = 0; brick < layer_bricks; ++brick) {
      const uint32_t* words = &bits[brick * kBrickWords];
      uint64_t set = 0;
      for (uint32_t w = 0; w < kBrickWords; ++w) set += uint64_t(std::popcount(words[w]));
      if (set == 0) continue;
      out.brick_index.push_back(uint64_t(bz) * layer_bricks + brick);
      out.brick_bits.insert(out.brick_bits.end(), words, words + kBrickWords);
      out.brick_rank.push_back(out.brick_rank.back() + set);
      if (!any_channel) continue;
      for (uint32_t w = 0; w < kBrickWords; ++w)
        for (uint32_t word = words[w]; word; word &= word - 1) {
          const uint64_t r = dense_rank[brick * kBrickVoxels + w * 32 + uint32_t(std::countr_zero(word))];
          if (has_count) out.count.push_back(dense.count[r]);
          if (has_sum) out.normal_sum.push_back(dense.normal_sum[r]);
          if (has_normal) out.normal.push_back(dense.normal[r]);
          if (has_material) out.material.push_back(dense.material[r]);
          if (has_color) out.color.push_back(dense.color[r]);
        }
    }
  }
  out.voxels_set = out.brick_rank.back();
  return out;
}

VoxelGrid to_dense(const SparseVoxelGrid& sparse) {
  VoxelGrid out;
  out.spec = sparse.spec;
  out.channels = sparse.channels;
  const uint64_t words = (sparse.spec.voxel_count() + 31) / 32;
  if (words > uint64_t(std::numeric_limits<std::ptrdiff_t>::max()) / sizeof(uint32_t))
    throw Error("the dense copy of a sparse grid does not fit in memory");
  out.occ.assign(size_t(words), 0u);
  sparse.for_each_set([&](uint32_t i, uint32_t j, uint32_t k, uint64_t) {
    const uint64_t l = sparse.spec.linear_index(i, j, k);
    out.occ[l >> 5] |= 1u << (l & 31);
  });
  out.voxels_set = sparse.voxels_set;
  const bool any_channel = !sparse.count.empty() || !sparse.normal_sum.empty() || !sparse.normal.empty() ||
                           !sparse.material.empty() || !sparse.color.empty();
  if (!any_channel) return out;
  // Dense rank of a voxel: the set bits of the words before its own, and of its word below it.
  std::vector<uint64_t> before(out.occ.size());
  uint64_t total = 0;
  for (size_t w = 0; w < out.occ.size(); ++w) {
    before[w] = total;
    total += uint64_t(std::popcount(out.occ[w]));
  }
  out.count.resize(sparse.count.size());
  out.normal_sum.resize(sparse.normal_sum.size());
  out.normal.resize(sparse.normal.size());
  out.material.resize(sparse.material.size());
  out.color.resize(sparse.color.size());
  sparse.for_each_set([&](uint32_t i, uint32_t j, uint32_t k, uint64_t r) {
    const uint64_t l = sparse.spec.linear_index(i, j, k);
    const uint64_t d =
        before[l >> 5] + uint64_t(std::popcount(out.occ[l >> 5] & ((uint32_t(1) << (l & 31)) - 1u)));
    if (!sparse.count.empty()) out.count[d] = sparse.count[r];
    if (!sparse.normal_sum.empty()) out.normal_sum[d] = sparse.normal_sum[r];
    if (!sparse.normal.empty()) out.normal[d] = sparse.normal[r];
    if (!sparse.material.empty()) out.material[d] = sparse.material[r];
    if (!sparse.color.empty()) out.color[d] = sparse.color[r];
  });
  return out;
}

}  // namespace voxr
