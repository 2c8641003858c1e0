/* slicemap_expand.cl — slicemap stage 2: every triangle writes one raster record per tile of its projected
 * bounding box, at its offset from the exclusive scan of slicemap_setup's counts. Only records inside the
 * window [window_begin, window_end) are written, so the host can raster the records in batches.
 * in:  tile_counts[t], tile_offsets[t] (exclusive scan), tile_info[t]
 * out: records[r - window_begin]
 * shape: one work item per triangle. */
#include "voxr_layout.h"

#ifndef WG_SIZE
#define WG_SIZE 256
#endif

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void slicemap_expand(
    uint triangle_count, __global const uint* tile_counts, __global const ulong* tile_offsets,
    __global const SlicemapTiles* tile_info, ulong window_begin, ulong window_end,
    __global SlicemapRecord* records) {
  const uint t = get_global_id(0);
  if (t >= triangle_count) return;
  const ulong offset = tile_offsets[t];
  const ulong begin = max(offset, window_begin);
  const ulong end = min(offset + tile_counts[t], window_end);
  if (begin >= end) return;
  const uint columns = tile_info[t].cols;
  for (ulong r = begin; r < end; ++r) {
    const uint q = (uint)(r - offset);
    SlicemapRecord rec;
    rec.triangle = t;
    rec.tile = ((q / columns) << 16) | (q % columns);
    records[r - window_begin] = rec;
  }
}
