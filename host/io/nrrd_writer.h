// NRRD (NRRD0004) output: raw little-endian data after the header in one file per channel. Occupancy is
// uint8 0/1 in `out`; each requested attribute channel goes to a sibling `<stem>.<channel><ext>`
// (out.nrrd -> out.count.nrrd uint32, out.normal.nrrd float 3-vector, out.material.nrrd uint32). Samples
// sit at voxel centres ("centers: cell"), `space origin` is the world centre of voxel (0,0,0) and
// `space directions` are the grid axes times the voxel size, in voxr's world coordinates as they are
// (declared right-anterior-superior so viewers such as 3D Slicer place them without a flip).
#pragma once

#include <filesystem>
#include <vector>

#include "grid/sparse_voxel_grid.h"
#include "grid/voxel_grid.h"

namespace voxr {

// Writes `out` and one sibling per attribute channel; returns them all, `out` first. Throws voxr::Error
// naming the file on failure; no file of the set is renamed into place unless all were written.
std::vector<std::filesystem::path> write_nrrd(const VoxelGrid& grid, const std::filesystem::path& out);
// The same files from the sparse grid (byte for byte what its dense grid writes), streamed a slice at a time
// from the bricks without a dense copy.
std::vector<std::filesystem::path> write_nrrd(const SparseVoxelGrid& grid, const std::filesystem::path& out);

// The sibling file of `out` holding `channel`: out.nrrd -> out.<channel>.nrrd.
std::filesystem::path nrrd_channel_path(const std::filesystem::path& out, Channel channel);

}  // namespace voxr
