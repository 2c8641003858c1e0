// What the volume format writers share: layout checks, the unit normal channel, and streaming of the sparse
// channels into dense arrays a bounded chunk at a time, so a 1024^3 grid never needs a dense copy in memory.
// Below io/volume_writer.h, which picks a writer by extension (the writers include only this header).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "grid/voxel_grid.h"
#include "io/atomic_file.h"

namespace voxr {

// Programmer-error checks (VOXR_CHECK) that the grid's occupancy and sparse channels agree in size.
void check_grid_layout(const VoxelGrid& grid);

// The unit normal of the set voxel of `rank`: grid.normal when present, else normalize(normal_sum).
class NormalChannel {
 public:
  explicit NormalChannel(const VoxelGrid& grid);
  glm::vec3 operator()(uint64_t rank) const;

 private:
  const VoxelGrid& grid_;
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

// Writes the grid as a dense array of `components` values of T per voxel in linear order (x fastest),
// zero where a voxel is empty and fill(T* values, rank) for set voxels, a bounded chunk at a time.
template <typename T, typename Fill>
void write_dense(AtomicFile& file, const VoxelGrid& grid, uint32_t components, Fill&& fill) {
  constexpr uint64_t kChunk = uint64_t(1) << 20;  // voxels per chunk, a multiple of 32
  const uint64_t n = grid.spec.voxel_count();
  std::vector<T> buffer(size_t(std::min(n, kChunk) * components));
  uint64_t rank = 0;
  for (uint64_t begin = 0; begin < n; begin += kChunk) {
    const uint64_t end = std::min(n, begin + kChunk);
    const size_t values = size_t((end - begin) * components);
    std::fill(buffer.begin(), buffer.begin() + values, T(0));
    for_each_set_in(grid, begin, end, rank, [&](uint64_t linear, uint64_t r) {
      fill(buffer.data() + (linear - begin) * components, r);
    });
    file.write(buffer.data(), values * sizeof(T));
  }
}

}  // namespace voxr
