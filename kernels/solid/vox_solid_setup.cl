/* vox_solid_setup.cl — per triangle: snap to the grid, find the column centres (i+1/2, j+1/2) its
 * projection on the xy plane may cover, and count its work items for vox_solid_cross.cl (one per block of
 * VOX_SOLID_ROWS rows of column centres).
 * Unlike the surface voxelizer, a triangle below or above the grid still counts: a crossing below the grid
 * flips the parity of the whole column, and the late mode counts every crossing of a column.
 * in:  positions (float4), triangles (uint4: indices, material)
 * out: snapped[t] (voxr_layout.h VoxSnappedTriangle), item_counts[t]; too_large counts triangles the host should
 *      have split (must stay 0).
 * shape: one work item per triangle. */
#include "voxr_layout.h"

/* Column ranges follow the pixel-centre rule. */
#undef VOXR_MODE
#define VOXR_MODE VOXR_MODE_CENTER
#include "vox_triangle.h"

#ifndef WG_SIZE
#define WG_SIZE 64
#endif
#ifndef VOX_SOLID_ROWS
#define VOX_SOLID_ROWS 4
#endif

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void vox_solid_setup(
    VoxGridParams grid, __global const float4* positions, __global const uint4* triangles,
    __global VoxSnappedTriangle* snapped, __global uint* item_counts, __global uint* too_large) {
  const uint t = get_global_id(0);
  if (t >= grid.triangle_count) return;
  VoxTri tri;
  vox_prepare_triangle(&tri, &grid, positions, triangles[t], snapped, t);
  uint count = 0;
  /* Edge-on triangles (no projected area) cover no column centre. */
  if (tri.n[2] != 0 && tri.first[0] <= tri.last[0] && tri.first[1] <= tri.last[1]) {
    if (vox_triangle_too_large(&tri))
      atomic_inc(too_large);
    else
      count = (uint)(tri.last[1] - tri.first[1]) / VOX_SOLID_ROWS + 1;
  }
  item_counts[t] = count;
}
