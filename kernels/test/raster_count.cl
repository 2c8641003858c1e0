/* raster_count.cl — a check of the coverage rule (tests, debugging): how many primitives cover each pixel
 * centre, front and back layers apart, through the same records and raster_coverage.h as raster_depth.cl.
 * in:  prims (raster_setup.cl), records (util/expand_copies.cl)
 * out: counts[2 (y * width + x) + (back ? 1 : 0)] += 1 per covering primitive (zeroed by the host)
 * shape: one work item per record. */
#include "raster_coverage.h"

#ifndef WG_SIZE
#define WG_SIZE 256
#endif

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void raster_count(
    uint width, uint height, __global const RasterPrim* prims, __global const CopyRecord* records,
    uint record_count, __global uint* counts) {
  const uint gid = get_global_id(0);
  if (gid >= record_count) return;
  const CopyRecord rec = records[gid];
  __global const RasterPrim* prim = prims + rec.triangle;
  const uint layer = (prim->flags & VOXR_PRIM_BACK) ? 1u : 0u;
  ulong mask = raster_tile_mask(prim, rec.cell, width, height);
  uint x, y;
  while (raster_next_pixel(&mask, rec.cell, &x, &y)) atomic_inc(counts + 2 * ((ulong)y * width + x) + layer);
}
