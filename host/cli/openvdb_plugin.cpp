#include "cli/openvdb_plugin.h"

#include <algorithm>

#include "io/openvdb_module.h"
#include "peers/openvdb_peer.h"
#include "util/error.h"

namespace voxr::cli {

bool openvdb_peer_available() {
  return openvdb_module_available();
}

std::optional<Table1Peer> load_openvdb_peer() {
  if (!openvdb_peer_available()) return std::nullopt;
  // io/openvdb_module.h keeps the plugin loaded for the life of the process.
  auto* entry = reinterpret_cast<decltype(&voxr_openvdb_mesh_to_volume)>(
      openvdb_module_symbol("voxr_openvdb_mesh_to_volume"));
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
