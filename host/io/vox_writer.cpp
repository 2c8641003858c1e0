#include "io/vox_writer.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "io/color_palette.h"
#include "io/grid_encoding.h"
#include "util/error.h"

namespace voxr {

namespace fs = std::filesystem;

static_assert(std::endian::native == std::endian::little, "the VOX writer emits host-order int32 as little");

namespace {

constexpr int32_t kVoxVersion = 150;

void write_chunk_header(AtomicFile& file, const char id[4], uint64_t content, uint64_t children) {
  file.write(id, 4);
  file.write_pod(int32_t(content));
  file.write_pod(int32_t(children));
}

// Palette entry for colour index c (1..255): index 1 (material 0, or no material channel) is light grey,
// the others spread over hues by the golden ratio so neighbouring material ids differ.
std::array<uint8_t, 4> palette_colour(uint32_t c) {
  if (c <= 1) return {200, 200, 200, 255};
  const float hue = std::fmod(float(c - 1) * 0.618034f, 1.0f) * 6.0f;
  const float s = 0.65f, v = 0.9f;
  const int sector = int(hue) % 6;
  const float f = hue - std::floor(hue);
  const float p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  float r, g, b;
  switch (sector) {
    case 0:
      r = v, g = t, b = p;
      break;
    case 1:
      r = q, g = v, b = p;
      break;
    case 2:
      r = p, g = v, b = t;
      break;
    case 3:
      r = p, g = q, b = v;
      break;
    case 4:
      r = t, g = p, b = v;
      break;
    default:
      r = v, g = p, b = q;
      break;
  }
  auto byte = [](float x) { return uint8_t(std::lround(std::clamp(x, 0.0f, 1.0f) * 255.0f)); };
  return {byte(r), byte(g), byte(b), 255};
}

}  // namespace

void check_vox_dims(const fs::path& out, const glm::uvec3& dims) {
  for (int a = 0; a < 3; ++a)
    if (dims[a] > kVoxMaxDim)
      fail(
          "{}: MagicaVoxel .vox holds at most {} voxels per axis, the grid has {} along {} ({}x{}x{}); "
          "write .nrrd or .vti instead",
          out.string(), kVoxMaxDim, dims[a], "xyz"[a], dims.x, dims.y, dims.z);
}

fs::path write_vox(const VoxelGrid& grid, const fs::path& out) {
  check_output_path(out);
  const GridSpec& spec = grid.spec;
  check_vox_dims(out, spec.dims);
  check_grid_layout(grid);

  const bool has_material = grid.channels.has(Channel::kMaterial);
  // The color channel wins over material: its palette is the median cut of the voxels' colours.
  const bool has_color = grid.channels.has(Channel::kColor);
  const ColorPalette palette = has_color ? median_cut_palette(grid.color, 255) : ColorPalette{};
  // At most 256^3 voxels: the XYZI payload (<= 64 MiB) is built in memory.
  std::vector<uint8_t> xyzi;
  xyzi.reserve(size_t(grid.voxels_set) * 4);
  const uint64_t row = spec.dims.x, slice = uint64_t(spec.dims.x) * spec.dims.y;
  grid.for_each_set([&](uint64_t linear, uint64_t rank) {
    const glm::uvec3 ijk(uint32_t(linear % row), uint32_t(linear / row % spec.dims.y),
                         uint32_t(linear / slice));
    const glm::uvec3 v = vox_coords(ijk, spec.dims);
    const uint32_t colour = has_color      ? 1 + palette.entry_of(grid.color[rank])
                            : has_material ? 1 + grid.material[rank] % 255
                                           : 1;
    xyzi.insert(xyzi.end(), {uint8_t(v.x), uint8_t(v.y), uint8_t(v.z), uint8_t(colour)});
  });

  const uint64_t size_bytes = 12 + 12;
  const uint64_t xyzi_bytes = 12 + 4 + xyzi.size();
  const uint64_t rgba_bytes = 12 + 256 * 4;

  AtomicFile file(out);
  file.write("VOX ");
  file.write_pod(kVoxVersion);
  write_chunk_header(file, "MAIN", 0, size_bytes + xyzi_bytes + rgba_bytes);

  const glm::uvec3 size = vox_size(spec.dims);
  write_chunk_header(file, "SIZE", 12, 0);
  for (int a = 0; a < 3; ++a) file.write_pod(int32_t(size[a]));

  write_chunk_header(file, "XYZI", 4 + xyzi.size(), 0);
  file.write_pod(int32_t(grid.voxels_set));
  file.write(xyzi.data(), xyzi.size());

  write_chunk_header(file, "RGBA", 256 * 4, 0);
  for (uint32_t i = 0; i < 256; ++i) {
    std::array<uint8_t, 4> rgba = i < 255 ? palette_colour(i + 1) : std::array<uint8_t, 4>{0, 0, 0, 255};
    if (has_color) {
      const uint32_t c = i < palette.entries.size() ? palette.entries[i] : 0xff000000u;
      rgba = {uint8_t(c), uint8_t(c >> 8), uint8_t(c >> 16), uint8_t(c >> 24)};
    }
    file.write(rgba.data(), rgba.size());
  }
  file.commit();
  return out;
}

}  // namespace voxr
