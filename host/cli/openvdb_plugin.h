// Loads the OpenVDB peer plugin (host/peers/openvdb_peer.h) from the voxr executable's folder, if it was
// built, as a Table 1 peer.
#pragma once

#include <optional>

#include "bench/table1.h"

namespace voxr::cli {

// Whether libvoxr_openvdb_peer.so is beside the executable (checked without loading it).
bool openvdb_peer_available();

// The peer, or nothing when the plugin is not there. Throws voxr::Error when it is there but cannot load.
std::optional<Table1Peer> load_openvdb_peer();

}  // namespace voxr::cli
