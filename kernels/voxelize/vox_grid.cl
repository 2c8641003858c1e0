/* vox_grid.cl — the "Grid" baseline (Llamas 2007, Table 1 of the papers): one launch per slab, in which
 * every triangle checks whether it reaches the slab and, if so, rasterizes all its rows there
 * (vox_scanline.h, the same exact rules as the slice method). Cost grows with slabs x triangles.
 * in:  snapped triangles (vox_setup.cl), the slab k; pass 1 also the ranked occupancy words
 * out: occupancy bits (pass 0), the attribute accumulators (pass 1; with colour also the colour sums, read
 *      from the mesh triangles and VOX_COLOR_PARAMS) or the triangle lists (pass 2)
 * shape: one work item per triangle, one launch per slab. */
#include "vox_scanline.h"

#ifndef WG_SIZE
#define WG_SIZE 64
#endif

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void vox_grid(
    VoxGridParams grid, __global const VoxSnappedTriangle* snapped, uint slab, __global uint* occ,
    __global const ulong* ranked, __global long* acc, __global uint* material, __global ulong* bricks,
    __global const uint4* triangles, VOX_COLOR_PARAMS) {
  const uint tri = get_global_id(0);
  if (tri >= grid.triangle_count) return;
  VoxTri t;
  const uint fetched = vox_fetch_triangle(&t, snapped, tri);
  /* pass 2 lists the triangle's mesh index in place of its material */
  const uint material_id = VOX_PASS == 2 ? snapped[tri].source : fetched;
  vox_derive(&t, &grid);
  if (!vox_triangle_active(&t) || (int)slab < t.first[2] || (int)slab > t.last[2]) return;
  VoxRule rule;
  vox_rule_init(&rule, &t, &grid);
  VoxWriter w;
  vox_writer_init(&w, material_id, &grid, occ, ranked, acc, material, bricks);
#if VOX_PASS == 1
  if (grid.channels & VOX_CH_NORMAL) vox_fixed_normal(vox_tri_normal(&t), &w.normal);
  if (grid.channels & VOX_CH_COLOR) {
    const uint source = snapped[tri].source;
    VOX_WRITER_COLOR_TRI(&w, triangles[source], source, &t);
  }
#endif
  vox_scan_slab(&t, &rule, &grid, (int)slab, t.first[1], t.last[1], 1, &w);
}
