// Loads the OpenVDB peer plugin (host/peers/openvdb_peer.h) from the voxr executable's folder, if it was
// built, as a Table 1 peer.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "bench/table1.h"

namespace voxr::cli {

// Whether libvoxr_openvdb_peer.so is beside the executable (checked without loading it).
bool openvdb_peer_available();

// The peer, or nothing when the plugin is not there. Throws voxr::Error when it is there but cannot load.
std::optional<Table1Peer> load_openvdb_peer();

// table1_methods() plus "openvdb" when the plugin is there: every voxelization method this build has.
std::vector<std::string> table1_methods_with_peers();

// Loads the peers `options.methods` names into options.peers. Throws voxr::Error when "openvdb" is named and
// the plugin is not there.
void add_table1_peers(Table1Options& options);

}  // namespace voxr::cli
