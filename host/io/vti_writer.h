// VTK XML ImageData (.vti) output, readable by ParaView and vtkXMLImageDataReader: version 1.0 with
// header_type="UInt64" (arrays beyond 4 GB are fine), little endian, all arrays appended raw after the XML.
// Points are voxel centres: WholeExtent 0..dims-1, Origin = world centre of voxel (0,0,0),
// Spacing = voxel size, Direction = the grid axes (row-major 3x3, columns are the axes, as VTK 9 reads it).
// PointData: "occupancy" UInt8 0/1, then per requested channel "count" UInt32, "normal" Float32 x3,
// "material" UInt32.
#pragma once

#include <filesystem>

#include "grid/sparse_voxel_grid.h"
#include "grid/voxel_grid.h"

namespace voxr {

// Writes `grid` to `out` and returns `out`. Throws voxr::Error naming `out` on failure.
std::filesystem::path write_vti(const VoxelGrid& grid, const std::filesystem::path& out);
// The same file from the sparse grid (byte for byte what its dense grid writes), streamed a slice at a time
// from the bricks without a dense copy.
std::filesystem::path write_vti(const SparseVoxelGrid& grid, const std::filesystem::path& out);

}  // namespace voxr
