// The exact conservative set of the INPUT triangles: every voxel whose closed box meets a closed triangle,
// on the input's own coordinates — vertices transformed to grid units in double precision from the float
// positions and the GridSpec, with no snapping — by the 13-axis separating-axis test (Akenine-Moller 2001,
// "Fast 3D triangle-box overlap testing") in double. Double rounding (about 1e-13 voxel here) is far below
// the conservative kernels' widening (snap_margin, at least 1/256 voxel), so "every voxel of this set is
// in the kernels' set" is a sound test of conservativeness; extra kernel voxels are those within the
// widening. Multi-threaded (std::thread, one share of the triangles each); occupancy only.
#pragma once

#include "core/grid_spec.h"
#include "core/triangle_soup.h"
#include "grid/voxel_grid.h"

namespace voxr {

// `widen` (voxels, >= 0) grows every box by that much on each side: with twice the snap bound it gives a
// set that must contain the conservative kernels' set (their extra voxels lie within the bound).
VoxelGrid reference_overlap(const TriangleSoup& soup, const GridSpec& grid, double widen = 0.0);

// Whether the closed box of voxel (i, j, k), grown by `widen` voxels on each side, meets the closed triangle
// with grid-unit vertices v.
bool overlap_exact(const glm::dvec3 (&v)[3], int64_t i, int64_t j, int64_t k, double widen = 0.0);

// Grid-unit coordinates of a world point in double precision (the exact transform of GridSpec).
glm::dvec3 grid_coords_exact(const GridSpec& grid, const glm::vec4& p);

}  // namespace voxr
