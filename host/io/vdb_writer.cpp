#include "io/vdb_writer.h"

#include <cstdlib>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "io/atomic_file.h"
#include "io/grid_encoding.h"
#include "io/openvdb_module.h"
#include "peers/vdb_write_abi.h"
#include "util/error.h"

namespace voxr {

namespace fs = std::filesystem;

namespace {

uint32_t vdb_compression(const fs::path& out) {
  const char* env = std::getenv("VOXR_VDB_COMPRESSION");
  if (!env) return kVoxrVdbDefault;
  const std::string name = env;
  if (name == "none") return kVoxrVdbNone;
  if (name == "zip") return kVoxrVdbZip;
  if (name == "blosc") return kVoxrVdbBlosc;
  fail("{}: VOXR_VDB_COMPRESSION='{}' is not none, zip or blosc", out.string(), name);
}

}  // namespace

void check_vdb_writer(const fs::path& out) {
  if (!openvdb_module_available())
    fail(
        "{}: writing .vdb needs the OpenVDB plugin {} (install libopenvdb-dev, configure with "
        "VOXR_WITH_OPENVDB=ON, rebuild)",
        out.string(),
        openvdb_module_path().empty() ? "libvoxr_openvdb_peer.so" : openvdb_module_path().string());
}

fs::path write_vdb(const SparseVoxelGrid& grid, const fs::path& out) {
  check_output_path(out);
  check_vdb_writer(out);
  check_grid_layout(grid);
  const uint32_t compression = vdb_compression(out);
  auto* entry = reinterpret_cast<decltype(&voxr_openvdb_write)>(openvdb_module_symbol("voxr_openvdb_write"));
  const GridSpec& spec = grid.spec;

  // The channels in the channel table's order; normals normalized when the grid holds only their sums.
  std::vector<VoxrVdbChannel> channels;
  std::vector<glm::vec3> normals;
  if (grid.channels.has(Channel::kCount))
    channels.push_back({"count", kVoxrVdbInt32, 1, grid.count.data(), 0});
  if (grid.channels.has(Channel::kNormal)) {
    const glm::vec3* values = grid.normal.data();
    if (grid.normal.size() != grid.voxels_set) {
      const NormalChannel normal(grid);
      normals.resize(size_t(grid.voxels_set));
      for (uint64_t r = 0; r < grid.voxels_set; ++r) normals[r] = normal(r);
      values = normals.data();
    }
    channels.push_back({"normal", kVoxrVdbFloat32, 3, values, 1});
  }
  if (grid.channels.has(Channel::kMaterial))
    channels.push_back({"material", kVoxrVdbInt32, 1, grid.material.data(), 0});
  // Colour as OpenVDB's registered types: `color` Vec3SGrid (RGB) and `alpha` FloatGrid, the 8-bit values /
  // 255.
  std::vector<glm::vec3> rgb;
  std::vector<float> alpha;
  if (grid.channels.has(Channel::kColor)) {
    rgb.resize(grid.color.size());
    alpha.resize(grid.color.size());
    for (size_t r = 0; r < grid.color.size(); ++r) {
      const uint32_t c = grid.color[r];
      rgb[r] = glm::vec3(float(c & 255u), float((c >> 8) & 255u), float((c >> 16) & 255u)) / 255.0f;
      alpha[r] = float(c >> 24) / 255.0f;
    }
    channels.push_back({"color", kVoxrVdbFloat32, 3, rgb.data(), 0});
    channels.push_back({"alpha", kVoxrVdbFloat32, 1, alpha.data(), 0});
  }

  VoxrVdbWrite w{};
  w.abi_version = VOXR_VDB_ABI_VERSION;
  for (int a = 0; a < 3; ++a) {
    w.dims[a] = spec.dims[a];
    w.brick_dims[a] = grid.brick_dims[a];
  }
  w.bricks = grid.bricks();
  w.brick_index = grid.brick_index.data();
  w.brick_bits = grid.brick_bits.data();
  w.brick_rank = grid.brick_rank.data();
  // Row a: one index step along a in world units; row 3: the world centre of voxel (0, 0, 0).
  const glm::dvec3 origin = spec.voxel_center_absolute(0, 0, 0);
  bool aligned = true;
  for (int a = 0; a < 3; ++a) {
    for (int c = 0; c < 3; ++c) {
      w.index_to_world[a * 4 + c] = double(spec.axes[a][c]) * double(spec.voxel_size);
      if (spec.axes[a][c] != (a == c ? 1.0f : 0.0f)) aligned = false;
    }
    w.index_to_world[a * 4 + 3] = 0.0;
  }
  w.index_to_world[12] = origin.x;
  w.index_to_world[13] = origin.y;
  w.index_to_world[14] = origin.z;
  w.index_to_world[15] = 1.0;
  w.axis_aligned = aligned ? 1 : 0;
  w.voxel_size = double(spec.voxel_size);
  w.compression = compression;
  w.channel_count = uint32_t(channels.size());
  w.channels = channels.data();
  w.creator = "voxr";

  AtomicFile file(out);
  file.close();  // OpenVDB writes the temporary through a stream of its own
  const std::string temp = file.temp_path().string();
  w.path = temp.c_str();
  char error[1024] = {};
  if (!entry(&w, error, sizeof error)) fail("{}: OpenVDB could not write the file: {}", out.string(), error);
  file.commit();
  return out;
}

fs::path write_vdb(const VoxelGrid& grid, const fs::path& out) {
  check_output_path(out);
  check_vdb_writer(out);
  return write_vdb(to_sparse(grid), out);
}

}  // namespace voxr
