// A voxelization result on the host. Occupancy is dense (one bit per voxel); the other channels are
// sparse: one entry per set voxel, in increasing linear index (the order of occupancy's set bits), so a
// 1024^3 grid with a few million surface voxels costs megabytes, not gigabytes.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/grid_spec.h"
#include "grid/channel_table.h"
#include "util/host_array.h"

namespace voxr {

struct VoxelGrid;
// The solid as one occupancy set (surface bits or interior bits), for the formats that hold a single set
// (.binvox, .vox): occ = occ | inside, no other channels.
VoxelGrid solid_occupancy(const VoxelGrid& grid);

struct VoxelGrid {
  GridSpec spec;
  ChannelSet channels;
  BitWords occ;  // bit (linear % 32) of word (linear / 32)
  uint64_t voxels_set = 0;

  // Sparse attributes, voxels_set entries each when the channel was requested, else empty.
  std::vector<uint32_t> count;         // triangles that wrote the voxel
  std::vector<glm::ivec3> normal_sum;  // fixed point, kNormalOne per unit normal of each triangle
  std::vector<glm::vec3> normal;       // normalized normal_sum (zero where the sum cancels)
  std::vector<uint32_t> material;      // largest material id among the triangles that wrote the voxel
  std::vector<uint32_t> color;         // RGBA8 (R in the low byte): mean base colour (channel_table.h)

  // Dense interior bits, laid out like occ, when channels has kInside (else empty): voxels whose centre a
  // solid mode judges inside (host/voxelize/solid_fill.h).
  BitWords inside;
  uint64_t inside_voxels = 0;

  // Host memory of the bits and channels, in bytes (as SparseVoxelGrid::memory_bytes).
  uint64_t memory_bytes() const {
    return (occ.size() + inside.size() + count.size() + material.size() + color.size()) * 4 +
           (normal_sum.size() + normal.size()) * 12;
  }

  bool occupied(uint64_t linear) const { return (occ[linear >> 5] >> (linear & 31)) & 1u; }
  bool occupied(uint32_t i, uint32_t j, uint32_t k) const { return occupied(spec.linear_index(i, j, k)); }
  bool is_inside(uint64_t linear) const { return (inside[linear >> 5] >> (linear & 31)) & 1u; }

  // Calls fn(linear_index, rank) for every set voxel in increasing linear order; rank indexes the sparse
  // channels.
  template <typename Fn>
  void for_each_set(Fn&& fn) const {
    uint64_t rank = 0;
    for (uint64_t w = 0; w < occ.size(); ++w) {
      uint32_t bits = occ[w];
      while (bits) {
        const int b = __builtin_ctz(bits);
        fn(w * 32 + uint64_t(b), rank++);
        bits &= bits - 1;
      }
    }
  }
};

// Bits [begin, end) of a dense bit array (occ or inside layout) as 0/1 bytes in out[0 .. end - begin).
void expand_bits(std::span<const uint32_t> bits, uint64_t begin, uint64_t end, uint8_t* out);

}  // namespace voxr
