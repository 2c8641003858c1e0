#include "io/binvox_writer.h"

#include <string>
#include <vector>

#include <fmt/format.h>

#include "core/error.h"
#include "io/volume_writer.h"

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

// Run-length encoder for binvox's (value, count) byte pairs, buffered.
class RunWriter {
 public:
  explicit RunWriter(OutputFile& file) : file_(file) { buffer_.reserve(kBuffer); }
  void push(uint8_t value, uint64_t count) {
    if (count == 0) return;
    if (run_ != 0 && value != value_) flush_run();
    value_ = value;
    run_ += count;
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
      if (buffer_.size() >= kBuffer) {
        file_.write(buffer_.data(), buffer_.size());
        buffer_.clear();
      }
    }
  }
  OutputFile& file_;
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

  OutputFile file(out);
  file.write(fmt::format("#binvox 1\ndim {} {} {}\ntranslate {} {} {}\nscale {}\ndata\n", d, d, d,
                         spec.origin.x, spec.origin.y, spec.origin.z, float(d) * spec.voxel_size));

  // binvox walks x slowest and y fastest, across voxr's x-fastest layout. Transpose a block of 64 x-values
  // at a time: masks[z*D + y] holds the occupancy of x0..x0+63 along row (y, z), so occupancy is read once
  // and in order, and the masks (8*D^2 bytes) are then walked per x.
  std::vector<uint64_t> masks(d * d);
  RunWriter runs(file);
  for (uint64_t x0 = 0; x0 < d; x0 += 64) {
    const uint32_t width = uint32_t(std::min<uint64_t>(64, d - x0));
    for (uint64_t z = 0; z < d; ++z)
      for (uint64_t y = 0; y < d; ++y) masks[z * d + y] = occupancy_bits(grid, (z * d + y) * d + x0, width);
    for (uint32_t dx = 0; dx < width; ++dx)
      for (uint64_t zy = 0; zy < d * d; ++zy) runs.push(uint8_t((masks[zy] >> dx) & 1u), 1);
  }
  runs.finish();
  file.commit();
  return out;
}

}  // namespace voxr
