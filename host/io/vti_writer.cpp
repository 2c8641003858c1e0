#include "io/vti_writer.h"

#include <bit>
#include <string>
#include <type_traits>

#include <fmt/format.h>

#include "io/grid_encoding.h"
#include "util/error.h"

namespace voxr {

namespace fs = std::filesystem;

static_assert(std::endian::native == std::endian::little, "the VTI writer emits host-order data as little");

namespace {

struct VtiArray {
  Channel channel;
  const char* name;
  const char* type;
  uint32_t components;
  uint64_t value_bytes;  // bytes per component
};

// The VTK type name and bytes of a channel table element type.
std::pair<const char*, uint64_t> vtk_type(ElementType type) {
  switch (type) {
    case ElementType::kUInt8:
      return {"UInt8", 1};
    case ElementType::kUInt32:
      return {"UInt32", 4};
    case ElementType::kFloat32:
      return {"Float32", 4};
  }
  throw InternalError("unhandled element type");
}

// One writer for both grids (io/grid_encoding.h): the dense arrays stream from either.
template <typename Grid>
fs::path write_vti_from(const Grid& grid, const fs::path& out) {
  check_output_path(out);
  check_grid_layout(grid);
  const GridSpec& spec = grid.spec;
  const uint64_t n = spec.voxel_count();

  // One array per present channel, named and typed by the channel table (occupancy always).
  std::vector<VtiArray> arrays;
  for (const ChannelInfo& info : kChannelTable) {
    if (!grid.channels.has(info.channel) && info.channel != Channel::kOcc) continue;
    const auto [type, bytes] = vtk_type(info.type);
    arrays.push_back({info.channel, info.array_name, type, info.components, bytes});
  }
  if constexpr (std::is_same_v<Grid, VoxelGrid>)
    if (grid.channels.has(Channel::kInside)) VOXR_CHECK_EQ(grid.inside.size(), grid.occ.size());

  const glm::dvec3 origin = spec.voxel_center_absolute(0, 0, 0);
  const std::string extent = fmt::format("0 {} 0 {} 0 {}", spec.dims.x - 1, spec.dims.y - 1, spec.dims.z - 1);
  std::string direction;
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col)
      direction += fmt::format("{}{}", direction.empty() ? "" : " ", spec.axes[col][row]);

  std::string xml = "<?xml version=\"1.0\"?>\n";
  xml += "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  xml += fmt::format(
      "  <ImageData WholeExtent=\"{}\" Origin=\"{} {} {}\" Spacing=\"{} {} {}\" Direction=\"{}\">\n", extent,
      origin.x, origin.y, origin.z, spec.voxel_size, spec.voxel_size, spec.voxel_size, direction);
  xml += fmt::format("    <Piece Extent=\"{}\">\n", extent);
  xml += fmt::format("      <PointData Scalars=\"{}\"{}>\n", channel_info(Channel::kOcc).array_name,
                     grid.channels.has(Channel::kNormal)
                         ? fmt::format(" Vectors=\"{}\"", channel_info(Channel::kNormal).array_name)
                         : "");
  uint64_t offset = 0;
  for (const VtiArray& a : arrays) {
    xml += fmt::format(
        "        <DataArray type=\"{}\" Name=\"{}\"{} format=\"appended\" offset=\"{}\"/>\n", a.type, a.name,
        a.components > 1 ? fmt::format(" NumberOfComponents=\"{}\"", a.components) : "", offset);
    offset += sizeof(uint64_t) + n * a.components * a.value_bytes;
  }
  xml += "      </PointData>\n";
  xml += "      <CellData>\n      </CellData>\n";
  xml += "    </Piece>\n";
  xml += "  </ImageData>\n";
  xml += "  <AppendedData encoding=\"raw\">\n   _";

  AtomicFile file(out);
  file.write(xml);
  for (const VtiArray& a : arrays) {
    file.write_pod(uint64_t(n * a.components * a.value_bytes));
    switch (a.channel) {
      case Channel::kOcc:
        write_dense<uint8_t>(file, grid, 1, [](uint8_t* v, uint64_t) { *v = 1; });
        break;
      case Channel::kCount:
        write_dense<uint32_t>(file, grid, 1, [&](uint32_t* v, uint64_t r) { *v = grid.count[r]; });
        break;
      case Channel::kNormal: {
        const NormalChannel normal(grid);
        write_dense<float>(file, grid, 3, [&](float* v, uint64_t r) {
          const glm::vec3 nv = normal(r);
          v[0] = nv.x;
          v[1] = nv.y;
          v[2] = nv.z;
        });
        break;
      }
      case Channel::kMaterial:
        write_dense<uint32_t>(file, grid, 1, [&](uint32_t* v, uint64_t r) { *v = grid.material[r]; });
        break;
      case Channel::kColor:
        write_dense<uint8_t>(file, grid, 4, [&](uint8_t* v, uint64_t r) {
          for (int q = 0; q < 4; ++q) v[q] = uint8_t(grid.color[r] >> (8 * q));
        });
        break;
      case Channel::kInside: {
        // Dense grids only (the sparse grid has no inside channel; check_grid_layout).
        if constexpr (std::is_same_v<Grid, VoxelGrid>) {
          std::vector<uint8_t> buffer(size_t(std::min(n, kDenseChunk)));
          for (uint64_t begin = 0; begin < n; begin += kDenseChunk) {
            const uint64_t end = std::min(n, begin + kDenseChunk);
            expand_bits(grid.inside, begin, end, buffer.data());
            file.write(buffer.data(), size_t(end - begin));
          }
        }
        break;
      }
    }
  }
  file.write("\n  </AppendedData>\n</VTKFile>\n");
  file.commit();
  return out;
}

}  // namespace

fs::path write_vti(const VoxelGrid& grid, const fs::path& out) {
  return write_vti_from(grid, out);
}

fs::path write_vti(const SparseVoxelGrid& grid, const fs::path& out) {
  return write_vti_from(grid, out);
}

}  // namespace voxr
