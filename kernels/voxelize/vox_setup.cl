/* vox_setup.cl — per triangle: snap to the grid, find the slabs and rows it may touch, and count its
 * copies (one per slab and block of rows_per_copy rows).
 * in:  positions (float4), triangles (uint4: indices, material); with VOX_SETUP_LIST, entry e is triangle
 *      list[e] (the large triangles vox_direct.cl leaves to this path) for e < *listed (the launch may run
 *      past the list: later entries count no copies), else triangle e
 * out: snapped[e] (what the later stages read instead of the mesh, and its mesh index), copy_counts[e],
 *      copy_boxes[e] (cells: block of rows across, slab down; util/expand_copies.cl);
 *      too_large counts triangles the host should have split (must stay 0).
 * shape: one work item per entry (grid.triangle_count entries). */
#include "voxr_layout.h"
#include "vox_triangle.h"

#ifndef WG_SIZE
#define WG_SIZE 64
#endif
#ifndef VOX_SETUP_LIST
#define VOX_SETUP_LIST 0
#endif

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void vox_setup(
    VoxGridParams grid, __global const float4* positions, __global const uint4* triangles,
    __global const uint* list, __global const uint* listed, __global VoxSnappedTriangle* snapped,
    __global uint* copy_counts, __global CopyBox* copy_boxes, __global uint* too_large) {
  const uint e = get_global_id(0);
  if (e >= grid.triangle_count) return;
  if (VOX_SETUP_LIST && e >= *listed) {
    copy_counts[e] = 0;
    return;
  }
  VoxTri tri;
  const uint source = VOX_SETUP_LIST ? list[e] : e;
  vox_prepare_triangle(&tri, &grid, positions, triangles[source], snapped, e);
  snapped[e].source = source;
  uint count = 0;
  CopyBox box = {0, 0};
  if (vox_triangle_active(&tri)) {
    if (vox_triangle_too_large(&tri)) {
      atomic_inc(too_large);
    } else {
      const uint blocks = vox_row_blocks(&tri, grid.rows_per_copy);
      count = (uint)(tri.last[2] - tri.first[2] + 1) * blocks;
      box.first = VOXR_CELL(0u, (uint)tri.first[2]);
      box.width = blocks;
    }
  }
  copy_counts[e] = count;
  copy_boxes[e] = box;
}
