// binvox output (Patrick Min's format, version 1), occupancy only, cubic grids only (D^3):
//   "#binvox 1\ndim D D D\ntranslate tx ty tz\nscale s\ndata\n" then (value, count 1..255) byte pairs
// run-length encoding the voxels in binvox order: y fastest, then z, then x (index = x*D*D + z*D + y).
// translate = world position of the grid corner (spec.anchor + spec.origin), scale = D * voxel size, so that binvox's
// (index + 0.5) / D * scale + translate is the voxel centre along each world axis. binvox has no rotation:
// a grid whose axes are not the world axes is written in its own frame.
#pragma once

#include <filesystem>

#include "grid/voxel_grid.h"

namespace voxr {

// Writes `grid` to `out` and returns `out`. Throws voxr::Error naming `out` for a non-cubic grid or a
// failed write.
std::filesystem::path write_binvox(const VoxelGrid& grid, const std::filesystem::path& out);
// Throws voxr::Error naming `out` unless binvox can hold a grid of `dims` (cubic).
void check_binvox_dims(const std::filesystem::path& out, const glm::uvec3& dims);

}  // namespace voxr
