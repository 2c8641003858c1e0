// The exact CPU reference for the slicemap baseline (semantics in voxelize/slicemap_voxelizer.h): for every
// triangle, every column centre of its bounding box is tested on its own (coverage with the top-left rule,
// depth as a 128-bit rational floored once) on the same snapped vertices the kernels use; local slicing runs
// the same loop twice (depth range, then bits). The voxel conversion gathers per voxel (which bits can hold a
// depth of the slab) where the kernel scatters per bit (which voxels its depths meet), so the two formulas
// check each other. Slow and simple on purpose: no tiles, no incremental stepping.
#pragma once

#include <cstdint>
#include <optional>

#include "core/grid_spec.h"
#include "core/triangle_soup.h"
#include "grid/voxel_grid.h"
#include "voxelize/slicemap_voxelizer.h"
#include "voxelize/snapped_triangle.h"

namespace voxr {

Slicemap reference_slicemap(const TriangleSoup& soup, const GridSpec& grid, SlicemapSlicing slicing);

// Voxel grid (channels: occ) of a slicemap: voxel (i, j, k) is set iff a set bit of column (i, j) holds a
// fixed-point depth in [k S, (k+1) S).
VoxelGrid reference_slicemap_voxels(const Slicemap& slicemap);

// The fragment of triangle t at column (i, j): its fixed-point depth zf = floor(S z) when t covers the
// column centre (top-left rule; never for a triangle edge-on to z), else nothing. Not clipped to the grid.
std::optional<int64_t> reference_fragment_depth(const SnappedTriangle& t, int64_t i, int64_t j);

// Bit of depth zf in a column of `slices` bits: uniform zf / S; local floor((zf - near) slices / (far - near
// + 1)) (near <= zf <= far).
uint32_t reference_slicemap_bit(SlicemapSlicing slicing, int64_t zf, int64_t near, int64_t far,
                                uint32_t slices);

}  // namespace voxr
