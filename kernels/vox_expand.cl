/* vox_expand.cl — the geometry shader's duplication: every triangle writes one record per copy
 * (slab, block of rows) at its offset from the exclusive scan of vox_setup's counts. Only records inside
 * the window [window_begin, window_end) are written, so the host can raster the copies in batches that fit
 * its memory budget.
 * in:  copy_counts[t], copy_offsets[t] (exclusive scan), copy_info[t]
 * out: copies[r - window_begin]
 * shape: one work item per triangle. */
#include "voxr_layout.h"

#ifndef WG_SIZE
#define WG_SIZE 64
#endif

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void vox_expand(
    uint triangle_count, __global const uint* copy_counts, __global const ulong* copy_offsets,
    __global const VoxCopyInfo* copy_info, ulong window_begin, ulong window_end, __global VoxCopy* copies) {
  const uint t = get_global_id(0);
  if (t >= triangle_count) return;
  const ulong offset = copy_offsets[t];
  const ulong begin = max(offset, window_begin);
  const ulong end = min(offset + copy_counts[t], window_end);
  if (begin >= end) return;
  const VoxCopyInfo info = copy_info[t];
  for (ulong r = begin; r < end; ++r) {
    const uint q = (uint)(r - offset);
    VoxCopy c;
    c.triangle = t;
    c.slice_block = (info.first_slab + q / info.row_blocks) | ((q % info.row_blocks) << 16);
    copies[r - window_begin] = c;
  }
}
