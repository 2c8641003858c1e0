// A voxelization result on the host in sparse bricks: memory proportional to the surface, not to the grid's
// volume, so 4096^3 to 16384^3 surface grids fit where dense bits (2^36 voxels = 8 GiB at 4096^3) do not.
//
// Layout: the grid is cut into 8^3 bricks (the leaf size of OpenVDB, whose LeafNode a brick maps onto). Only
// bricks holding at least one set voxel are stored, in increasing linear brick index (bz * brick_dims.y + by)
// * brick_dims.x + bx, i.e. z slowest, like the dense grid's voxels. A brick's 512 occupancy bits are 16
// 32-bit words; voxel (x, y, z) of the brick (0..7 each) is bit b = x + 8 * (y + 8 * z) (x fastest, as in the
// dense grid): bit (b % 32) of word (b / 32). The sparse channels (count, normal, material) hold one entry
// per set voxel in *brick order*: bricks in the order above, within a brick in increasing b. brick_rank[i]
// is the number of set voxels before brick i, so voxel b of brick i has rank brick_rank[i] + popcount of the
// brick's bits below b.
//
// Produced by the sparse voxelizer (host/voxelize/sparse_voxelizer.h) or converted from a dense VoxelGrid
// (to_sparse); to_dense goes back (tests, small grids).
#pragma once

#include <bit>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/grid_spec.h"
#include "grid/channel_table.h"
#include "grid/voxel_grid.h"

namespace voxr {

constexpr uint32_t kBrickEdge = 8;                                       // voxels along a brick's edge
constexpr uint32_t kBrickVoxels = kBrickEdge * kBrickEdge * kBrickEdge;  // 512
constexpr uint32_t kBrickWords = kBrickVoxels / 32;                      // 16 occupancy words per brick

// Bricks along each axis of a grid of `dims` voxels (the last brick of an axis may stick out of the grid;
// its voxels past dims are never set).
inline glm::uvec3 brick_dims_of(const glm::uvec3& dims) {
  return (dims + glm::uvec3(kBrickEdge - 1)) / kBrickEdge;
}

struct SparseVoxelGrid {
  GridSpec spec;
  ChannelSet channels;  // occ, count, normal, material, color (no inside: the solid fill runs on dense grids)
  glm::uvec3 brick_dims{0};
  std::vector<uint64_t> brick_index;  // linear brick index of each stored brick, increasing
  std::vector<uint32_t> brick_bits;   // kBrickWords per stored brick
  std::vector<uint64_t> brick_rank;   // set voxels before each brick; bricks() + 1 entries
  uint64_t voxels_set = 0;

  // Sparse attributes in brick order, voxels_set entries each when the channel is present, else empty.
  std::vector<uint32_t> count;
  std::vector<glm::ivec3> normal_sum;  // fixed point, kNormalOne per unit normal of each triangle
  std::vector<glm::vec3> normal;       // normalized normal_sum (zero where the sum cancels)
  std::vector<uint32_t> material;
  std::vector<uint32_t> color;  // RGBA8 (R in the low byte)

  size_t bricks() const { return brick_index.size(); }
  // The brick's (bx, by, bz) from its linear brick index.
  glm::uvec3 brick_coord(uint64_t linear_brick) const {
    return {uint32_t(linear_brick % brick_dims.x), uint32_t((linear_brick / brick_dims.x) % brick_dims.y),
            uint32_t(linear_brick / (uint64_t(brick_dims.x) * brick_dims.y))};
  }
  // Host memory of the bricks and channels, in bytes.
  uint64_t memory_bytes() const;
  // Whether voxel (i, j, k) is set (a binary search over the bricks).
  bool occupied(uint32_t i, uint32_t j, uint32_t k) const;

  // Calls fn(i, j, k, rank) for every set voxel in brick order; rank indexes the sparse channels.
  template <typename Fn>
  void for_each_set(Fn&& fn) const {
    uint64_t rank = 0;
    for (size_t b = 0; b < bricks(); ++b) {
      const glm::uvec3 base = brick_coord(brick_index[b]) * kBrickEdge;
      for (uint32_t w = 0; w < kBrickWords; ++w) {
        uint32_t bits = brick_bits[b * kBrickWords + w];
        while (bits) {
          const uint32_t v = w * 32 + uint32_t(std::countr_zero(bits));
          fn(base.x + (v & 7u), base.y + ((v >> 3) & 7u), base.z + (v >> 6), rank++);
          bits &= bits - 1;
        }
      }
    }
  }
};

// The dense grid's set voxels and sparse channels as bricks (channels reordered to brick order). Inside bits
// are not carried (SparseVoxelGrid has no inside channel). One pass over the dense bits.
SparseVoxelGrid to_sparse(const VoxelGrid& dense);
// The sparse grid as a dense VoxelGrid (channels back in linear order). Throws voxr::Error when the dense
// bits would not fit in memory a vector can address.
VoxelGrid to_dense(const SparseVoxelGrid& sparse);

}  // namespace voxr
