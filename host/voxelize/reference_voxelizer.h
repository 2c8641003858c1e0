// The exact CPU reference for the slice family of voxelizers: for every triangle, every voxel of its bounding
// box is tested on its own with the full predicate — the 13-axis triangle/box separating-axis test in 128-bit
// integers against the voxel box widened by the snap margin (conservative, snapped_triangle.h snap_margin),
// or the pixel-centre/top-left/slab-depth rule (center) — on the same snapped vertices the kernels use.
// Slow and simple on purpose: it shares no loop structure with the kernels. The color channel's sample and
// mean are the kernels' own (kernels/common/vox_color.h, compiled here too), so colours agree bit for bit.
#pragma once

#include "core/grid_spec.h"
#include "core/triangle_soup.h"
#include "grid/voxel_grid.h"
#include "voxelize/raster_mode.h"
#include "voxelize/snapped_triangle.h"

namespace voxr {

VoxelGrid reference_voxelize(const TriangleSoup& soup, const GridSpec& grid, RasterMode mode,
                             ChannelSet channels);

// The single-voxel predicates, exposed for tests.
// Whether the closed box of voxel (i, j, k), widened by `margin` 1/VOXR_SUBVOXEL units on every side, meets
// the closed snapped triangle.
bool reference_conservative_overlap(const SnappedTriangle& t, int64_t i, int64_t j, int64_t k,
                                    int64_t margin);
bool reference_center_hit(const SnappedTriangle& t, int64_t i, int64_t j, int64_t k);
// Whether the centre of column (i, j) lies inside the triangle's projection on the slicing plane (top-left
// ties; an edge-on triangle covers nothing).
bool reference_center_covers(const SnappedTriangle& t, int64_t i, int64_t j);
// Whether the z-line through the centre of column (i, j) crosses the triangle under the centre rule (top-left
// ties), and the slab k containing the crossing (a crossing on a slab boundary belongs to the slab above).
bool reference_center_crossing(const SnappedTriangle& t, int64_t i, int64_t j, int64_t* k);

}  // namespace voxr
