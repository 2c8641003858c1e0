#include "io/nrrd_writer.h"

#include <bit>
#include <memory>
#include <span>
#include <string>
#include <type_traits>

#include <fmt/format.h>

#include "io/grid_encoding.h"
#include "util/error.h"

namespace voxr {

namespace fs = std::filesystem;

static_assert(std::endian::native == std::endian::little, "the NRRD writer emits host-order data as little");

namespace {

// Shortest text that reads back as the same float or double.
template <typename Vec>
std::string vec_text(const Vec& v) {
  return fmt::format("({},{},{})", v.x, v.y, v.z);
}

// `type` is the NRRD type name; `components` > 1 adds a leading N-vector axis.
std::string nrrd_header(const GridSpec& spec, const char* type, uint32_t components, const char* content) {
  const bool vector = components > 1;
  const char* pre = vector ? "none " : "";
  std::string h = "NRRD0004\n";
  h += "# Complete NRRD file format specification at:\n# http://teem.sourceforge.net/nrrd/format.html\n";
  h += fmt::format("content: {}\n", content);
  h += fmt::format("type: {}\n", type);
  h += fmt::format("dimension: {}\n", vector ? 4 : 3);
  h += fmt::format("sizes: {}{} {} {}\n", vector ? fmt::format("{} ", components) : "", spec.dims.x,
                   spec.dims.y, spec.dims.z);
  // After `sizes`: VTK's vtkNrrdReader resets the dimension to 3 on reading `space`.
  h += "space: right-anterior-superior\n";
  h += fmt::format("space directions: {}{} {} {}\n", pre, vec_text(spec.axes[0] * spec.voxel_size),
                   vec_text(spec.axes[1] * spec.voxel_size), vec_text(spec.axes[2] * spec.voxel_size));
  h += fmt::format("kinds: {}domain domain domain\n", vector ? fmt::format("{}-vector ", components) : "");
  h += fmt::format("centers: {}cell cell cell\n", pre);
  h += "endian: little\n";
  h += "encoding: raw\n";
  h += fmt::format("space origin: {}\n", vec_text(spec.voxel_center_absolute(0, 0, 0)));
  h += "\n";
  return h;
}

// Bits as uint8 0/1, a bounded chunk at a time.
void write_dense_bits(AtomicFile& file, std::span<const uint32_t> bits, uint64_t n) {
  std::vector<uint8_t> buffer(size_t(std::min(n, kDenseChunk)));
  for (uint64_t begin = 0; begin < n; begin += kDenseChunk) {
    const uint64_t end = std::min(n, begin + kDenseChunk);
    expand_bits(bits, begin, end, buffer.data());
    file.write(buffer.data(), size_t(end - begin));
  }
}

// "voxr <array name>": the content line voxr-view reads the array name from.
std::string content(Channel channel) {
  return fmt::format("voxr {}", channel_info(channel).array_name);
}

}  // namespace

fs::path nrrd_channel_path(const fs::path& out, Channel channel) {
  fs::path p = out.parent_path() / out.stem();
  p += fmt::format(".{}{}", channel_name(channel), out.extension().string());
  return p;
}

namespace {

// One writer for both grids (io/grid_encoding.h): the dense arrays stream from either.
template <typename Grid>
std::vector<fs::path> write_nrrd_from(const Grid& grid, const fs::path& out) {
  check_output_path(out);
  check_grid_layout(grid);
  const GridSpec& spec = grid.spec;

  std::vector<std::unique_ptr<AtomicFile>> files;
  files.push_back(std::make_unique<AtomicFile>(out));
  files.back()->write(nrrd_header(spec, "uint8", 1, content(Channel::kOcc).c_str()));
  write_dense<uint8_t>(*files.back(), grid, 1, [](uint8_t* v, uint64_t) { *v = 1; });
  files.back()->close();

  if (grid.channels.has(Channel::kCount)) {
    files.push_back(std::make_unique<AtomicFile>(nrrd_channel_path(out, Channel::kCount)));
    files.back()->write(nrrd_header(spec, "uint32", 1, content(Channel::kCount).c_str()));
    write_dense<uint32_t>(*files.back(), grid, 1, [&](uint32_t* v, uint64_t r) { *v = grid.count[r]; });
    files.back()->close();
  }
  if (grid.channels.has(Channel::kNormal)) {
    const NormalChannel normal(grid);
    files.push_back(std::make_unique<AtomicFile>(nrrd_channel_path(out, Channel::kNormal)));
    files.back()->write(nrrd_header(spec, "float", 3, content(Channel::kNormal).c_str()));
    write_dense<float>(*files.back(), grid, 3, [&](float* v, uint64_t r) {
      const glm::vec3 n = normal(r);
      v[0] = n.x;
      v[1] = n.y;
      v[2] = n.z;
    });
    files.back()->close();
  }
  if (grid.channels.has(Channel::kMaterial)) {
    files.push_back(std::make_unique<AtomicFile>(nrrd_channel_path(out, Channel::kMaterial)));
    files.back()->write(nrrd_header(spec, "uint32", 1, content(Channel::kMaterial).c_str()));
    write_dense<uint32_t>(*files.back(), grid, 1, [&](uint32_t* v, uint64_t r) { *v = grid.material[r]; });
    files.back()->close();
  }
  if (grid.channels.has(Channel::kColor)) {
    files.push_back(std::make_unique<AtomicFile>(nrrd_channel_path(out, Channel::kColor)));
    files.back()->write(nrrd_header(spec, "uint8", 4, content(Channel::kColor).c_str()));
    write_dense<uint8_t>(*files.back(), grid, 4, [&](uint8_t* v, uint64_t r) {
      for (int q = 0; q < 4; ++q) v[q] = uint8_t(grid.color[r] >> (8 * q));
    });
    files.back()->close();
  }
  if constexpr (std::is_same_v<Grid, VoxelGrid>) {  // the sparse grid has no inside channel
    if (grid.channels.has(Channel::kInside)) {
      VOXR_CHECK_EQ(grid.inside.size(), grid.occ.size());
      files.push_back(std::make_unique<AtomicFile>(nrrd_channel_path(out, Channel::kInside)));
      files.back()->write(nrrd_header(spec, "uint8", 1, content(Channel::kInside).c_str()));
      write_dense_bits(*files.back(), grid.inside, spec.voxel_count());
      files.back()->close();
    }
  }

  std::vector<fs::path> written;
  for (auto& f : files) {
    f->commit();
    written.push_back(f->path());
  }
  return written;
}

}  // namespace

std::vector<fs::path> write_nrrd(const VoxelGrid& grid, const fs::path& out) {
  return write_nrrd_from(grid, out);
}

std::vector<fs::path> write_nrrd(const SparseVoxelGrid& grid, const fs::path& out) {
  return write_nrrd_from(grid, out);
}

}  // namespace voxr
