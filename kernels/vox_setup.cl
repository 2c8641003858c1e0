/* vox_setup.cl — per triangle: snap to the grid, find the slabs and rows it may touch, and count its
 * copies (one per slab and block of rows_per_copy rows).
 * in:  positions (float4), triangles (uint4: indices, material)
 * out: snapped[3t..3t+2] (fixed-point vertices, material; what the later stages read instead of the mesh),
 *      copy_counts[t], copy_info[t] = (first slab, row blocks); too_large counts triangles the host should
 *      have split (must stay 0).
 * shape: one work item per triangle. */
#include "voxr_layout.h"
#include "vox_triangle.h"

#ifndef WG_SIZE
#define WG_SIZE 64
#endif

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void vox_setup(
    VoxGridParams grid, __global const float4* positions, __global const uint4* triangles,
    __global int4* snapped, __global uint* copy_counts, __global uint2* copy_info, __global uint* too_large) {
  const uint t = get_global_id(0);
  if (t >= grid.triangle_count) return;
  VoxTri tri;
  vox_prepare_triangle(&tri, &grid, positions, triangles, t, snapped);
  uint count = 0;
  uint2 info = (uint2)(0, 0);
  if (vox_triangle_active(&tri)) {
    if (vox_triangle_too_large(&tri)) {
      atomic_inc(too_large);
    } else {
      const uint blocks = vox_row_blocks(&tri, grid.rows_per_copy);
      count = (uint)(tri.last[2] - tri.first[2] + 1) * blocks;
      info = (uint2)((uint)tri.first[2], blocks);
    }
  }
  copy_counts[t] = count;
  copy_info[t] = info;
}
