/* slicemap_setup.cl — slicemap (Eisemann & Decoret 2006), stage 1 of 4: per triangle, snap to the grid,
 * find the column centres of its projected bounding box and count its raster work items, one per tile of
 * SLICEMAP_TILE_ROWS x SLICEMAP_TILE_COLS column centres (a triangle covering thousands of columns becomes
 * many work items, never one long loop).
 * in:  positions (float4), triangles (uint4: indices, material)
 * out: snapped[t] (voxr_layout.h VoxSnappedTriangle, as vox_setup.cl stores it), tile_counts[t],
 *      tile_boxes[t] (cells: column tile across, row tile down); 0 tiles when the triangle covers no column
 *      centre of the grid (outside it, or edge-on to the slicing axis); too_large counts triangles the host
 *      should have split (must stay 0).
 * shape: one work item per triangle. */
#include "voxr_layout.h"

/* Column centres and half-open depth slabs: the centre rule of vox_triangle.h. */
#define VOXR_MODE VOXR_MODE_CENTER
#include "vox_triangle.h"

#ifndef WG_SIZE
#define WG_SIZE 256
#endif
#ifndef SLICEMAP_TILE_ROWS
#define SLICEMAP_TILE_ROWS 8
#endif
#ifndef SLICEMAP_TILE_COLS
#define SLICEMAP_TILE_COLS 8
#endif

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void slicemap_setup(
    VoxGridParams grid, __global const float4* positions, __global const uint4* triangles,
    __global VoxSnappedTriangle* snapped, __global uint* tile_counts, __global CopyBox* tile_boxes, __global uint* too_large) {
  const uint t = get_global_id(0);
  if (t >= grid.triangle_count) return;
  VoxTri tri;
  vox_prepare_triangle(&tri, &grid, positions, triangles[t], snapped, t);
  uint count = 0;
  CopyBox box = {0, 0};
  if (vox_triangle_active(&tri)) {
    if (vox_triangle_too_large(&tri)) {
      atomic_inc(too_large);
    } else {
      const uint rows = (uint)(tri.last[1] - tri.first[1]) / SLICEMAP_TILE_ROWS + 1;
      box.width = (uint)(tri.last[0] - tri.first[0]) / SLICEMAP_TILE_COLS + 1;
      count = rows * box.width;
    }
  }
  tile_counts[t] = count;
  tile_boxes[t] = box;
}
