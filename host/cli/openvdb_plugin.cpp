#include "cli/openvdb_plugin.h"

#include <dlfcn.h>

#include <algorithm>
#include <filesystem>

#include "cli/process.h"
#include "peers/openvdb_peer.h"
#include "util/error.h"

namespace voxr::cli {

namespace {

std::filesystem::path plugin_path() {
  const std::filesystem::path folder = executable_folder();
  return folder.empty() ? folder : folder / "libvoxr_openvdb_peer.so";
}

}  // namespace

bool openvdb_peer_available() {
  const std::filesystem::path plugin = plugin_path();
  std::error_code ec;
  return !plugin.empty() && std::filesystem::exists(plugin, ec);
}

std::optional<Table1Peer> load_openvdb_peer() {
  if (!openvdb_peer_available()) return std::nullopt;
  const std::filesystem::path plugin = plugin_path();
  // Kept loaded for the life of the process (OpenVDB's registries must outlive every call).
  void* handle = dlopen(plugin.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) fail("{}: cannot load the OpenVDB peer: {}", plugin.string(), dlerror());
  auto* entry =
      reinterpret_cast<decltype(&voxr_openvdb_mesh_to_volume)>(dlsym(handle, "voxr_openvdb_mesh_to_volume"));
  if (!entry) fail("{}: no voxr_openvdb_mesh_to_volume in the OpenVDB peer", plugin.string());
  return Table1Peer([entry](const TriangleSoup& soup, const GridSpec& grid, VoxelizeStats* stats) {
    const std::array<float, 12> m = grid.world_to_grid();
    VoxelGrid out;
    double ms = 0.0;
    char error[512] = {};
    if (!entry(&soup, &grid, m.data(), &out, &ms, error, sizeof error))
      fail("OpenVDB mesh-to-volume failed: {}", error);
    if (stats) {
      *stats = VoxelizeStats{};
      stats->triangles = soup.triangle_count();
      stats->voxels_set = out.voxels_set;
      stats->kernels_ms = ms;
      stats->wall_ms = ms;
    }
    return out;
  });
}

std::vector<std::string> table1_methods_with_peers() {
  std::vector<std::string> methods = table1_methods();
  if (openvdb_peer_available()) methods.push_back("openvdb");
  return methods;
}

void add_table1_peers(Table1Options& options) {
  if (std::find(options.methods.begin(), options.methods.end(), "openvdb") == options.methods.end()) return;
  std::optional<Table1Peer> peer = load_openvdb_peer();
  if (!peer)
    fail("method openvdb: libvoxr_openvdb_peer.so is not beside voxr (install libopenvdb-dev, rebuild)");
  options.peers["openvdb"] = std::move(*peer);
}

}  // namespace voxr::cli
