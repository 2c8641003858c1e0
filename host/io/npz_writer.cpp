#include "io/npz_writer.h"

#include <minizip/zip.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "io/atomic_file.h"
#include "io/grid_encoding.h"
#include "util/error.h"

namespace voxr {

namespace fs = std::filesystem;

static_assert(std::endian::native == std::endian::little, "the NPZ writer emits host-order data as little");

namespace {

// The .npy header (format 1.0) of an array of `descr` and `shape` ("(N, 3)", "()"), padded with spaces to a
// multiple of 64 bytes as NumPy writes it.
std::string npy_header(const char* descr, const std::string& shape) {
  std::string dict = fmt::format("{{'descr': '{}', 'fortran_order': False, 'shape': {}, }}", descr, shape);
  const size_t unpadded = 10 + dict.size() + 1;
  dict.append((64 - unpadded % 64) % 64, ' ');
  dict += '\n';
  std::string h("\x93NUMPY\x01\x00", 8);
  const uint16_t len = uint16_t(dict.size());
  h.append(reinterpret_cast<const char*>(&len), 2);
  return h + dict;
}

// The zip being written, on the AtomicFile's temporary (minizip seeks back to fill in each entry's sizes,
// so it writes the temporary through a file of its own; the AtomicFile renames it into place).
class NpzArchive {
 public:
  // `total` bounds the archive's size: past 4 GiB every entry is ZIP64 (an entry's local header offset may
  // pass 4 GiB even when the entry itself is small).
  NpzArchive(AtomicFile& file, uint64_t total) : file_(file), zip64_(total >= kZip64From) {
    zip_ = zipOpen64(file.temp_path().c_str(), APPEND_STATUS_CREATE);
    if (!zip_) fail("{}: cannot create the zip archive", file.path().string());
  }
  ~NpzArchive() {
    if (zip_) zipClose(zip_, nullptr);
  }
  NpzArchive(const NpzArchive&) = delete;
  NpzArchive& operator=(const NpzArchive&) = delete;

  // Starts entry `name`.npy holding `bytes` bytes of data after the header.
  void begin(const std::string& name, const char* descr, const std::string& shape, uint64_t bytes) {
    const std::string header = npy_header(descr, shape);
    zip_fileinfo info{};
    info.tmz_date.tm_year = 1980;  // a fixed date: the same grid gives the same bytes
    info.tmz_date.tm_mday = 1;
    const int zip64 = zip64_ || header.size() + bytes >= kZip64From ? 1 : 0;
    check(zipOpenNewFileInZip64(zip_, (name + ".npy").c_str(), &info, nullptr, 0, nullptr, 0, nullptr, 0, 0,
                                zip64),
          "cannot start entry " + name);
    entry_ = name;
    write(header.data(), header.size());
  }
  void write(const void* data, uint64_t bytes) {
    const char* p = static_cast<const char*>(data);
    while (bytes > 0) {
      const unsigned n = unsigned(std::min<uint64_t>(bytes, uint64_t(1) << 30));
      check(zipWriteInFileInZip(zip_, p, n), "cannot write entry " + entry_);
      p += n;
      bytes -= n;
    }
  }
  void end() { check(zipCloseFileInZip(zip_), "cannot finish entry " + entry_); }
  // A whole array in one entry.
  template <typename T>
  void array(const std::string& name, const char* descr, const std::string& shape,
             std::span<const T> values) {
    begin(name, descr, shape, values.size_bytes());
    write(values.data(), values.size_bytes());
    end();
  }
  void close() {
    const int status = zipClose(zip_, nullptr);
    zip_ = nullptr;
    check(status, "cannot finish the zip archive");
  }

 private:
  void check(int status, const std::string& what) const {
    if (status != ZIP_OK) fail("{}: {} (minizip error {})", file_.path().string(), what, status);
  }
  static constexpr uint64_t kZip64From = 0xffffffffull - (uint64_t(1) << 20);  // headers and directory
  AtomicFile& file_;
  bool zip64_;
  zipFile zip_ = nullptr;
  std::string entry_;
};

}  // namespace

fs::path write_npz(const SparseVoxelGrid& grid, const fs::path& out) {
  check_output_path(out);
  check_grid_layout(grid);
  const GridSpec& spec = grid.spec;
  const uint64_t n = grid.voxels_set;

  AtomicFile file(out);
  file.close();  // minizip writes the temporary through its own handle
  // Array bytes: ijk, then per voxel count 4, normal 12, material 4, color 4; the small arrays and headers
  // well within the 1 MiB kZip64From leaves.
  const uint64_t total =
      n *
      (12 + (grid.channels.has(Channel::kCount) ? 4 : 0) + (grid.channels.has(Channel::kNormal) ? 12 : 0) +
       (grid.channels.has(Channel::kMaterial) ? 4 : 0) + (grid.channels.has(Channel::kColor) ? 4 : 0));
  NpzArchive zip(file, total);

  // ijk a bounded chunk at a time, from the bricks.
  zip.begin("ijk", "<i4", fmt::format("({}, 3)", n), n * 3 * sizeof(int32_t));
  {
    std::vector<int32_t> buffer;
    buffer.reserve(3 * kDenseChunk + 3 * kBrickVoxels);
    grid.for_each_set([&](uint32_t i, uint32_t j, uint32_t k, uint64_t) {
      buffer.insert(buffer.end(), {int32_t(i), int32_t(j), int32_t(k)});
      if (buffer.size() >= 3 * kDenseChunk) {
        zip.write(buffer.data(), buffer.size() * sizeof(int32_t));
        buffer.clear();
      }
    });
    zip.write(buffer.data(), buffer.size() * sizeof(int32_t));
  }
  zip.end();

  const std::string column = fmt::format("({},)", n);
  if (grid.channels.has(Channel::kCount)) zip.array<uint32_t>("count", "<u4", column, grid.count);
  if (grid.channels.has(Channel::kNormal)) {
    if (grid.normal.size() == n) {
      zip.array<float>("normal", "<f4", fmt::format("({}, 3)", n),
                       std::span<const float>(reinterpret_cast<const float*>(grid.normal.data()), 3 * n));
    } else {
      const NormalChannel normal(grid);
      zip.begin("normal", "<f4", fmt::format("({}, 3)", n), n * 3 * sizeof(float));
      std::vector<glm::vec3> buffer;
      for (uint64_t begin = 0; begin < n; begin += kDenseChunk) {
        buffer.clear();
        for (uint64_t r = begin; r < std::min(n, begin + kDenseChunk); ++r) buffer.push_back(normal(r));
        zip.write(buffer.data(), buffer.size() * sizeof(glm::vec3));
      }
      zip.end();
    }
  }
  if (grid.channels.has(Channel::kMaterial)) zip.array<uint32_t>("material", "<u4", column, grid.material);
  // RGBA8 packed with R in the low byte is, little-endian, the bytes R, G, B, A: an N x 4 uint8 array.
  if (grid.channels.has(Channel::kColor))
    zip.array<uint8_t>("color", "|u1", fmt::format("({}, 4)", n),
                       std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(grid.color.data()), 4 * n));

  const uint32_t dims[3] = {spec.dims.x, spec.dims.y, spec.dims.z};
  zip.array<uint32_t>("dims", "<u4", "(3,)", dims);
  const double voxel_size[1] = {double(spec.voxel_size)};
  zip.array<double>("voxel_size", "<f8", "()", voxel_size);
  const glm::dvec3 o = spec.voxel_center_absolute(0, 0, 0);
  const double origin[3] = {o.x, o.y, o.z};
  zip.array<double>("origin", "<f8", "(3,)", origin);
  double axes[9];
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c)
      axes[a * 3 + c] = double(spec.axes[a][c]);  // row a = column a of GridSpec::axes
  zip.array<double>("axes", "<f8", "(3, 3)", axes);
  zip.close();
  file.commit();
  return out;
}

fs::path write_npz(const VoxelGrid& grid, const fs::path& out) {
  check_output_path(out);
  return write_npz(to_sparse(grid), out);
}

}  // namespace voxr
