// Finding and loading the OpenVDB plugin, libvoxr_openvdb_peer.so (host/peers: the benchmark peer and the
// .vdb writer). It is built beside the voxr executable when libopenvdb-dev is installed and loaded by dlopen
// only when needed, so no other voxr process maps OpenVDB and its dependencies (TBB, Blosc, Boost, ...).
#pragma once

#include <filesystem>

namespace voxr {

// Where the plugin is looked for: $VOXR_OPENVDB_PLUGIN when set (tests point it into the build tree, or at
// nothing), else the first libvoxr_openvdb_peer.so found beside the running executable, beside the shared
// library this code is in (libvoxr.so in a program or the Python package), in its bin/ or in its ../bin/;
// when none is there, the one beside the executable (for the message). Empty when nothing is known.
std::filesystem::path openvdb_module_path();

// Whether the plugin file is there (checked without loading it).
bool openvdb_module_available();

// The symbol `name` of the plugin, loaded on first use and kept loaded for the life of the process (OpenVDB's
// registries must outlive every call). Throws voxr::Error naming the plugin when it is missing, cannot be
// loaded, or lacks the symbol.
void* openvdb_module_symbol(const char* name);

}  // namespace voxr
