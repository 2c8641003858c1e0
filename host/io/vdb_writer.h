// OpenVDB .vdb output through the OpenVDB plugin (io/openvdb_module.h, peers/vdb_write_abi.h): voxr itself
// never links OpenVDB. Grids, all with one transform (index (i, j, k) -> the world centre of voxel (i, j, k):
// a scale-translate map for axis-aligned grids, an affine map for rotated ones):
//   "occupancy"  BoolGrid   true and active at every set voxel. A BoolGrid, not a MaskGrid: it carries a
//                           value any reader can sample or convert to float (mask grids carry topology
//                           only, and are the newer type some readers skip); not tried in Blender or
//                           ParaView here. Blender's Volume object renders a grid chosen by name.
//   "count"      Int32Grid  OpenVDB registers no unsigned grid; voxr's uint32 values, bit for bit
//   "normal"     Vec3SGrid  unit normal in index space (vector type covariant-normalize, not world space)
//   "material"   Int32Grid  as count
// Each grid's metadata: creator "voxr", voxr_dims (the grid's dimensions as Vec3i); the file's: creator.
// Leaves are built from the sparse grid's bricks (one 8^3 brick = one leaf). The interior (--solid's inside
// channel) is not written. Compression: Blosc when OpenVDB has it, else zip (docs/cli.md, "Which format",
// has the measurements); $VOXR_VDB_COMPRESSION=none|zip|blosc overrides.
#pragma once

#include <filesystem>

#include "grid/sparse_voxel_grid.h"
#include "grid/voxel_grid.h"

namespace voxr {

// Writes `grid` to `out` and returns `out`. Throws voxr::Error naming `out` when the OpenVDB plugin is
// missing or fails; nothing is left under `out` then.
std::filesystem::path write_vdb(const SparseVoxelGrid& grid, const std::filesystem::path& out);
// The dense grid through to_sparse (memory of its set voxels, not of the volume).
std::filesystem::path write_vdb(const VoxelGrid& grid, const std::filesystem::path& out);

// Throws voxr::Error naming `out` when the OpenVDB plugin is not there (checked before a voxelization).
void check_vdb_writer(const std::filesystem::path& out);

}  // namespace voxr
