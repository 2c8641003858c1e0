// What the volume format writers share: layout checks, the unit normal channel, and streaming of a grid into
// dense arrays a bounded chunk at a time, so a 1024^3 grid never needs a dense copy in memory. Both host
// grids feed the same writer code: the dense VoxelGrid (occupancy bits in linear order, channels in linear
// order) and the SparseVoxelGrid (8^3 bricks, channels in brick order). The writers are templates over the
// grid type (or take the sparse grid alone) and reach a grid only through the functions below and the members
// both grids share (spec, channels, voxels_set, count, normal_sum, normal, material), so one writer serves
// both. Below io/volume_writer.h, which picks a writer by extension (the writers include only this header).
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "grid/sparse_voxel_grid.h"
#include "grid/voxel_grid.h"
#include "io/atomic_file.h"

namespace voxr {

// Programmer-error checks (VOXR_CHECK) that the grid's occupancy and sparse channels agree in size.
void check_grid_layout(const VoxelGrid& grid);
void check_grid_layout(const SparseVoxelGrid& grid);

// The unit normal of the set voxel of `rank`: grid.normal when present, else normalize(normal_sum). Works on
// either grid (rank in the grid's own channel order).
class NormalChannel {
 public:
  template <typename Grid>
  explicit NormalChannel(const Grid& grid)
      : normal_(grid.normal), normal_sum_(grid.normal_sum), from_sum_(grid.normal.size() != grid.voxels_set) {
    check(grid.voxels_set);
  }
  glm::vec3 operator()(uint64_t rank) const;

 private:
  void check(uint64_t voxels_set) const;
  std::span<const glm::vec3> normal_;
  std::span<const glm::ivec3> normal_sum_;
  bool from_sum_;
};

// Calls fn(linear, rank) for the set voxels with linear index in [begin, end), in increasing order. `rank`
// is the rank of the first set voxel at or after `begin` and is advanced past the range.
template <typename Fn>
void for_each_set_in(const VoxelGrid& grid, uint64_t begin, uint64_t end, uint64_t& rank, Fn&& fn) {
  if (begin >= end) return;
  for (uint64_t w = begin >> 5; w <= (end - 1) >> 5; ++w) {
    uint32_t bits = grid.occ[w];
    if (w == begin >> 5) bits &= ~0u << (begin & 31);
    if (w == (end - 1) >> 5 && ((end - 1) & 31) != 31) bits &= (2u << ((end - 1) & 31)) - 1u;
    while (bits) {
      const uint32_t b = uint32_t(__builtin_ctz(bits));
      fn(w * 32 + b, rank++);
      bits &= bits - 1;
    }
  }
}

// The stored bricks [first, last) of the sparse grid that meet rows [y0, y1) of slice z (all of them lie in
// brick layer z / 8, contiguous in the brick order).
std::pair<size_t, size_t> sparse_bricks_in_rows(const SparseVoxelGrid& grid, uint32_t z, uint32_t y0,
                                                uint32_t y1);

// Calls fn(x, y, rank) for the set voxels of slice z with y in [y0, y1), brick by brick (not in linear
// order); rank indexes the sparse grid's channels (brick order).
template <typename Fn>
void for_each_set_in_rows(const SparseVoxelGrid& grid, uint32_t z, uint32_t y0, uint32_t y1, Fn&& fn) {
  const auto [first, last] = sparse_bricks_in_rows(grid, z, y0, y1);
  const uint32_t plane = z & 7u;  // words 2 * plane and 2 * plane + 1 hold the brick's slice z
  for (size_t b = first; b < last; ++b) {
    const glm::uvec3 base = grid.brick_coord(grid.brick_index[b]) * kBrickEdge;
    const uint32_t* words = &grid.brick_bits[b * kBrickWords];
    uint64_t rank = grid.brick_rank[b];
    for (uint32_t w = 0; w < 2 * plane; ++w) rank += uint64_t(std::popcount(words[w]));
    for (uint32_t half = 0; half < 2; ++half) {
      uint32_t bits = words[2 * plane + half];
      while (bits) {
        const uint32_t v = half * 32 + uint32_t(std::countr_zero(bits));  // x + 8 * y within the slice
        const uint32_t y = base.y + (v >> 3);
        if (y >= y0 && y < y1) fn(base.x + (v & 7u), y, rank);
        ++rank;
        bits &= bits - 1;
      }
    }
  }
}

constexpr uint64_t kDenseChunk = uint64_t(1) << 20;  // voxels per chunk of a dense array, a multiple of 32

// Writes the grid as a dense array of `components` values of T per voxel in linear order (x fastest),
// zero where a voxel is empty and fill(T* values, rank) for set voxels, a bounded chunk at a time.
template <typename T, typename Fill>
void write_dense(AtomicFile& file, const VoxelGrid& grid, uint32_t components, Fill&& fill) {
  const uint64_t n = grid.spec.voxel_count();
  std::vector<T> buffer(size_t(std::min(n, kDenseChunk) * components));
  uint64_t rank = 0;
  for (uint64_t begin = 0; begin < n; begin += kDenseChunk) {
    const uint64_t end = std::min(n, begin + kDenseChunk);
    const size_t values = size_t((end - begin) * components);
    std::fill(buffer.begin(), buffer.begin() + values, T(0));
    for_each_set_in(grid, begin, end, rank, [&](uint64_t linear, uint64_t r) {
      fill(buffer.data() + (linear - begin) * components, r);
    });
    file.write(buffer.data(), values * sizeof(T));
  }
}

// The same bytes from the sparse grid, without a dense copy: slice by slice (rows of a slice when a slice
// exceeds a chunk), filled from the bricks of the slice's brick layer.
template <typename T, typename Fill>
void write_dense(AtomicFile& file, const SparseVoxelGrid& grid, uint32_t components, Fill&& fill) {
  const glm::uvec3 d = grid.spec.dims;
  const uint32_t rows = uint32_t(std::clamp<uint64_t>(kDenseChunk / d.x, 1, d.y));  // rows per chunk
  std::vector<T> buffer(size_t(uint64_t(rows) * d.x * components));
  for (uint32_t z = 0; z < d.z; ++z)
    for (uint32_t y0 = 0; y0 < d.y; y0 += rows) {
      const uint32_t y1 = std::min(d.y, y0 + rows);
      const size_t values = size_t(uint64_t(y1 - y0) * d.x * components);
      std::fill(buffer.begin(), buffer.begin() + values, T(0));
      for_each_set_in_rows(grid, z, y0, y1, [&](uint32_t x, uint32_t y, uint64_t r) {
        fill(buffer.data() + (uint64_t(y - y0) * d.x + x) * components, r);
      });
      file.write(buffer.data(), values * sizeof(T));
    }
}

}  // namespace voxr
