/* raster_depth.cl — the visibility buffer: one 64-bit word per pixel, (float bits of z_ndc) << 32 | triangle,
 * cleared to all ones and lowered by 64-bit atomic min (cl_khr_int64_extended_atomics), so the nearest
 * fragment wins and equal depths go to the lower triangle id, whatever order the work items run in.
 *   raster_clear: every word to ~0 (no triangle). shape: one work item per pixel.
 *   raster_depth: the covered pixels of one record (raster_coverage.h). shape: one work item per record.
 *   raster_depth_peel: raster_depth for depth peeling (Everitt 2001): a fragment is kept only where the
 *     previous layer's visibility buffer has a triangle and the fragment lies farther than its depth by more
 *     than epsilon_ulps float steps (depths are non-negative, so their bits order as uints; the same
 *     triangle gives the same depth bits at a pixel, so it is never kept twice). shape: as raster_depth.
 * in:  prims (raster_setup.cl), records and how many (util/expand_copies.cl; the launch may run past them),
 *      previous (peel: the last layer's words)
 * out: visibility[y * width + x] */
#pragma OPENCL EXTENSION cl_khr_int64_extended_atomics : enable

#include "raster_coverage.h"

#ifndef WG_SIZE
#define WG_SIZE 256
#endif

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void raster_clear(__global ulong* visibility,
                                                                                uint pixel_count) {
  const uint i = get_global_id(0);
  if (i < pixel_count) visibility[i] = ~0ul;
}

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void raster_depth(
    uint width, uint height, __global const RasterPrim* prims, __global const CopyRecord* records,
    __global const uint* record_count, __global ulong* visibility) {
  const uint gid = get_global_id(0);
  if (gid >= *record_count) return;
  const CopyRecord rec = records[gid];
  __global const RasterPrim* prim = prims + rec.triangle;
  ulong mask = raster_tile_mask(prim, rec.cell, width, height);
  uint x, y;
  while (raster_next_pixel(&mask, rec.cell, &x, &y)) {
    const float depth = raster_depth_at(prim, x, y, width, height);
    const ulong word = raster_visibility_word(depth, rec.triangle);
    __global ulong* slot = visibility + (ulong)y * width + x;
#ifdef __ENDIAN_LITTLE__
    /* Words only decrease, so a stored depth already below this fragment's makes the atomic unnecessary.
     * The depth half alone is read: a 32-bit load is never torn, a plain 64-bit one might be. */
    if (((__global const uint*)slot)[1] < as_uint(depth)) continue;
#endif
    atom_min(slot, word);
  }
}

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void raster_depth_peel(
    uint width, uint height, __global const RasterPrim* prims, __global const CopyRecord* records,
    __global const uint* record_count, __global const ulong* previous, uint epsilon_ulps,
    __global ulong* visibility) {
  const uint gid = get_global_id(0);
  if (gid >= *record_count) return;
  const CopyRecord rec = records[gid];
  __global const RasterPrim* prim = prims + rec.triangle;
  ulong mask = raster_tile_mask(prim, rec.cell, width, height);
  uint x, y;
  while (raster_next_pixel(&mask, rec.cell, &x, &y)) {
    const ulong pixel = (ulong)y * width + x;
    const ulong before = previous[pixel];
    if (before == ~0ul) continue; /* the previous layer is empty here: so is every later one */
    const float depth = raster_depth_at(prim, x, y, width, height);
    if ((ulong)as_uint(depth) <= (before >> 32) + epsilon_ulps) continue;
    atom_min(visibility + pixel, raster_visibility_word(depth, rec.triangle));
  }
}
