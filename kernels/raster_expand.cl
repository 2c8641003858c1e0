/* raster_expand.cl — stage 3 of the kernel rasterizer: one record (triangle, tile) per raster work item. Work
 * item i writes record r = window_begin + i: its triangle is the last t with tile_offsets[t] <= r (a binary
 * search over the exclusive scan of raster_setup's counts, so a triangle with thousands of tiles is expanded
 * by as many work items), its tile the (r - tile_offsets[t])-th of the triangle's tile box, row by row.
 * in:  tile_offsets (exclusive scan, ulong), prims (first_tile, tiles_x)
 * out: records[i], i < window_count
 * shape: one work item per record of the window. */
#include "voxr_layout.h"

#ifndef WG_SIZE
#define WG_SIZE 256
#endif

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void raster_expand(
    uint triangle_count, __global const ulong* tile_offsets, __global const RasterPrim* prims,
    ulong window_begin, uint window_count, __global RasterRecord* records) {
  const uint i = get_global_id(0);
  if (i >= window_count || triangle_count == 0) return;
  const ulong r = window_begin + i;
  uint lo = 0, hi = triangle_count; /* tile_offsets[lo] <= r (tile_offsets[0] = 0); the answer is below hi */
  while (hi - lo > 1) {
    const uint mid = lo + (hi - lo) / 2;
    if (tile_offsets[mid] <= r)
      lo = mid;
    else
      hi = mid;
  }
  const uint q = (uint)(r - tile_offsets[lo]);
  const uint first = prims[lo].first_tile, across = prims[lo].tiles_x;
  RasterRecord rec;
  rec.triangle = lo;
  rec.tile = ((first & 0xffffu) + q % across) | (((first >> 16) + q / across) << 16);
  records[i] = rec;
}
