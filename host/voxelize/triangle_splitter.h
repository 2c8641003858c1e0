// The exact integer predicates of the kernels hold for triangles up to VOXR_MAX_TRIANGLE_EXTENT voxels
// long on each axis. Larger triangles (a ground plane cropped by --bounds, grids beyond 2000 voxels) are
// split at edge midpoints until they fit; pieces that miss the grid are dropped.
#pragma once

#include <optional>

#include "core/grid_spec.h"
#include "core/triangle_soup.h"

namespace voxr {

// Extent (voxels) above which a triangle is split; below VOXR_MAX_TRIANGLE_EXTENT with room for rounding.
constexpr float kSplitExtentVoxels = 2000.0f;

// Which pieces may be dropped. kGrid (surface voxelization): pieces that miss the grid. kColumns (solid
// fill, which counts every crossing of a column, also below and above the grid): only pieces that miss the
// grid's columns; triangles wholly below or above the grid are moved onto a plane half a voxel outside it.
enum class SplitCull { kGrid, kColumns };

// The soup with oversized triangles replaced by their pieces (and, for kColumns, far triangles flattened),
// or nothing when no triangle needs it. `split` receives the number of input triangles changed.
std::optional<TriangleSoup> split_oversized_triangles(const TriangleSoup& soup, const GridSpec& grid,
                                                      uint64_t* split = nullptr,
                                                      SplitCull cull = SplitCull::kGrid);

}  // namespace voxr
