// Writing a voxel grid to a volume file, the format chosen by the extension: .nrrd, .vti, .binvox, .vox
// (dense formats), .vdb (OpenVDB, through the plugin of io/openvdb_module.h) and .npz (a NumPy sparse voxel
// list). Either host grid is written: the dense VoxelGrid or the SparseVoxelGrid; for every format the sparse
// grid writes byte for byte what the dense grid it came from writes (.vdb: the same grids and values; OpenVDB
// puts a random UUID in each file). .nrrd and .vti stream from the bricks a slice at a time (no dense copy);
// .vdb and .npz are sparse formats (the dense grid goes through to_sparse); .binvox and .vox, small formats,
// go through to_dense. Every file is an AtomicFile (io/atomic_file.h): it appears only once it is complete.
// The format writers' shared plumbing is io/grid_encoding.h, below this header (the writers do not include
// it).
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include <glm/glm.hpp>

#include "core/grid_spec.h"
#include "grid/sparse_voxel_grid.h"
#include "grid/voxel_grid.h"

namespace voxr {

// Writes `grid` to `out` in the format its extension names (case-insensitive) and returns every file
// written (NRRD writes one sibling file per attribute channel). The folder must exist. Throws voxr::Error
// naming `out` for an unknown extension, a missing folder, a grid the format cannot hold, or a failed write;
// on error no partial file is left under any of the output names.
std::vector<std::filesystem::path> write_volume(const VoxelGrid& grid, const std::filesystem::path& out);
// The same for the sparse grid (no inside channel: .binvox and .vox get the surface set).
std::vector<std::filesystem::path> write_volume(const SparseVoxelGrid& grid,
                                                const std::filesystem::path& out);

// Adapts a grid request to what the format of `out` holds: .binvox stores cubic grids only, so a request by
// resolution (no explicit dims) becomes resolution^3 around the scene. Other formats: unchanged.
void fit_request_to_format(GridRequest& request, const std::filesystem::path& out);

// Everything write_volume would refuse before any work is done: folder, extension, grid size the format can
// hold, the OpenVDB plugin for .vdb. Throws voxr::Error naming `out`.
void check_volume_output(const std::filesystem::path& out, const glm::uvec3& dims);

}  // namespace voxr
