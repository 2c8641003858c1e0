#include "io/binvox_writer.h"

#include <algorithm>
#include <bit>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "io/grid_encoding.h"
#include "util/error.h"

namespace voxr {

namespace fs = std::filesystem;

namespace {

// `count` (<= 64) occupancy bits starting at linear index `pos`, bit t of the result = voxel pos + t.
uint64_t occupancy_bits(const VoxelGrid& grid, uint64_t pos, uint32_t count) {
  uint64_t v = 0;
  uint32_t got = 0;
  while (got < count) {
    const uint32_t off = uint32_t(pos & 31);
    const uint32_t take = std::min(32u - off, count - got);
    const uint32_t word = grid.occ[pos >> 5] >> off;
    const uint32_t mask = take == 32 ? ~0u : (1u << take) - 1u;
    v |= uint64_t(word & mask) << got;
    got += take;
    pos += take;
  }
  return v;
}

// Transposes a 64 x 64 bit matrix in place: bit c of a[r] <-> bit r of a[c] (Hacker's Delight 7-3).
void transpose64(uint64_t (&a)[64]) {
  uint64_t m = 0x00000000ffffffffull;
  for (int j = 32; j != 0; j >>= 1, m ^= m << j)
    for (int k = 0; k < 64; k = (k + j + 1) & ~j) {
      const uint64_t t = ((a[k] >> j) ^ a[k + j]) & m;
      a[k] ^= t << j;
      a[k + j] ^= t;
    }
}

// Run-length encoder for binvox's (value, count) byte pairs, fed whole 64-bit words of the voxel stream.
class RunWriter {
 public:
  explicit RunWriter(AtomicFile& file) : file_(file) { buffer_.reserve(kBuffer + 512); }
  // The next `n` (1..64) voxels of the stream: bit t of `bits` is voxel t (bits above n are ignored).
  void push_word(uint64_t bits, uint32_t n) {
    while (n > 0) {
      const uint8_t bit = uint8_t(bits & 1u);
      const uint32_t len =
          std::min<uint32_t>(n, uint32_t(bit ? std::countr_one(bits) : std::countr_zero(bits)));
      if (run_ != 0 && bit != value_) flush_run();
      value_ = bit;
      run_ += len;
      n -= len;
      bits = len >= 64 ? 0 : bits >> len;
    }
  }
  void finish() {
    flush_run();
    file_.write(buffer_.data(), buffer_.size());
    buffer_.clear();
  }

 private:
  static constexpr size_t kBuffer = size_t(1) << 20;
  void flush_run() {
    while (run_ > 0) {
      const uint8_t c = uint8_t(std::min<uint64_t>(run_, 255));
      buffer_.push_back(value_);
      buffer_.push_back(c);
      run_ -= c;
    }
    if (buffer_.size() >= kBuffer) {
      file_.write(buffer_.data(), buffer_.size());
      buffer_.clear();
    }
  }
  AtomicFile& file_;
  std::vector<uint8_t> buffer_;
  uint8_t value_ = 0;
  uint64_t run_ = 0;
};

}  // namespace

void check_binvox_dims(const fs::path& out, const glm::uvec3& dims) {
  if (dims.x != dims.y || dims.y != dims.z)
    fail("{}: binvox holds cubic grids only, this grid is {}x{}x{}; write .nrrd or .vti instead",
         out.string(), dims.x, dims.y, dims.z);
}

fs::path write_binvox(const VoxelGrid& grid, const fs::path& out) {
  check_output_path(out);
  const GridSpec& spec = grid.spec;
  check_binvox_dims(out, spec.dims);
  check_grid_layout(grid);
  const uint64_t d = spec.dims.x;

  AtomicFile file(out);
  const glm::dvec3 corner = spec.anchor + glm::dvec3(spec.origin);
  file.write(fmt::format("#binvox 1\ndim {} {} {}\ntranslate {} {} {}\nscale {}\ndata\n", d, d, d, corner.x,
                         corner.y, corner.z, float(d) * spec.voxel_size));

  // binvox walks x slowest and y fastest, across voxr's x-fastest layout. For each block of 64 x-values
  // and each z, 64 x 64 tiles (64 y-rows of 64 x-bits) are transposed into 64 words along y, one per x,
  // stored x-major; the stream is then run-length encoded a word at a time.
  const uint64_t words_y = (d + 63) / 64;
  std::vector<uint64_t> stream(64 * d * words_y);  // [dx][z][y word] for the current x block
  RunWriter runs(file);
  for (uint64_t x0 = 0; x0 < d; x0 += 64) {
    const uint32_t width = uint32_t(std::min<uint64_t>(64, d - x0));
    for (uint64_t z = 0; z < d; ++z)
      for (uint64_t wy = 0; wy < words_y; ++wy) {
        uint64_t tile[64] = {};
        const uint64_t y0 = wy * 64, rows = std::min<uint64_t>(64, d - y0);
        for (uint64_t r = 0; r < rows; ++r) tile[r] = occupancy_bits(grid, (z * d + y0 + r) * d + x0, width);
        transpose64(tile);
        for (uint32_t dx = 0; dx < width; ++dx) stream[(dx * d + z) * words_y + wy] = tile[dx];
      }
    for (uint32_t dx = 0; dx < width; ++dx)
      for (uint64_t z = 0; z < d; ++z)
        for (uint64_t wy = 0; wy < words_y; ++wy)
          runs.push_word(stream[(dx * d + z) * words_y + wy], uint32_t(std::min<uint64_t>(64, d - wy * 64)));
  }
  runs.finish();
  file.commit();
  return out;
}

}  // namespace voxr
