// MagicaVoxel .vox output (version 150): "VOX " 150, then a MAIN chunk whose children are SIZE (three
// int32), XYZI (int32 count, then x, y, z, colour index bytes per set voxel) and RGBA (256 colours; entry i
// is colour index i + 1). Each axis holds at most 256 voxels. With the color channel, the palette is the
// median cut of the voxels' colours (io/color_palette.h, at most 255 entries; unused entries opaque black)
// and a voxel's index is 1 + its colour's entry; else colour index = 1 + material % 255 when the grid has the
// material channel, else 1.
//
// Axes: MagicaVoxel is right-handed with z up; voxr scenes are right-handed with y up. A voxel (x, y, z)
// is written at vox (x, Dz-1-z, y): a rotation of +90 degrees about x, so y-up scenes stand upright and
// are not mirrored (swapping y and z alone would mirror them). SIZE is (Dx, Dz, Dy) accordingly.
#pragma once

#include <filesystem>

#include <glm/glm.hpp>

#include "grid/voxel_grid.h"

namespace voxr {

constexpr uint32_t kVoxMaxDim = 256;

// Writes `grid` to `out` and returns `out`. Throws voxr::Error naming `out` and the axis when an axis
// exceeds 256 voxels, or on a failed write.
std::filesystem::path write_vox(const VoxelGrid& grid, const std::filesystem::path& out);
// Throws voxr::Error naming `out` unless .vox can hold a grid of `dims` (at most 256 per axis).
void check_vox_dims(const std::filesystem::path& out, const glm::uvec3& dims);

// voxr voxel (i, j, k) of a grid of `dims` -> MagicaVoxel coordinates (see above).
inline glm::uvec3 vox_coords(const glm::uvec3& ijk, const glm::uvec3& dims) {
  return {ijk.x, dims.z - 1 - ijk.z, ijk.y};
}
inline glm::uvec3 vox_size(const glm::uvec3& dims) {
  return {dims.x, dims.z, dims.y};
}

}  // namespace voxr
