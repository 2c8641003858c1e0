/* vox_raster.cl — the scanline stage of the slice voxelizer: each work item takes one copy record
 * (triangle; cell: block of rows_per_copy rows, slab) written by util/expand_copies.cl and rasterizes it
 * (vox_scanline.h: exact rules, passes, channels).
 * in:  snapped triangles (vox_setup.cl), copy records and how many (the launch may run past them); pass 1
 *      also the ranked occupancy words
 * out: occupancy bits (pass 0), the attribute accumulators (pass 1; with colour also the colour sums, read
 *      from the mesh triangles and VOX_COLOR_PARAMS) or the triangle lists (pass 2)
 * shape: one work item per copy record. */
#include "vox_scanline.h"

#ifndef WG_SIZE
#define WG_SIZE 64
#endif

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void vox_raster(
    VoxGridParams grid, __global const VoxSnappedTriangle* snapped, __global const CopyRecord* copies, __global const uint* copy_count,
    __global uint* occ, __global const ulong* ranked, __global long* acc, __global uint* material,
    __global ulong* bricks, __global const uint4* triangles, VOX_COLOR_PARAMS) {
  const uint gid = get_global_id(0);
  if (gid >= *copy_count) return;
  const CopyRecord rec = copies[gid];
  VoxTri t;
  const uint fetched = vox_fetch_triangle(&t, snapped, rec.triangle);
  /* pass 2 lists the triangle's mesh index in place of its material */
  const uint material_id = VOX_PASS == 2 ? snapped[rec.triangle].source : fetched;
  vox_derive(&t, &grid);
  const int row_first = t.first[1] + (int)(VOXR_CELL_COLUMN(rec.cell) * grid.rows_per_copy);
  const int row_last = min(t.last[1], row_first + (int)grid.rows_per_copy - 1);
  VoxRule rule;
  vox_rule_init(&rule, &t, &grid);
  VoxWriter w;
  vox_writer_init(&w, material_id, &grid, occ, ranked, acc, material, bricks);
#if VOX_PASS == 1
  if (grid.channels & VOX_CH_NORMAL) vox_fixed_normal(vox_tri_normal(&t), &w.normal);
  if (grid.channels & VOX_CH_COLOR) {
    const uint source = snapped[rec.triangle].source;
    VOX_WRITER_COLOR_TRI(&w, triangles[source], source, &t);
  }
#endif
  vox_scan_slab(&t, &rule, &grid, (int)VOXR_CELL_ROW(rec.cell), row_first, row_last, 1, &w);
}
