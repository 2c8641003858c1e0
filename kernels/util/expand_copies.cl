/* expand_copies.cl — the one duplication step of the slice voxelizer (a triangle's slabs x blocks of rows),
 * the slicemap voxelizer (its tiles of column centres) and the kernel rasterizer (its 8x8-pixel tiles):
 * one record per copy, one work item per record. A triangle's copies are the cells of its CopyBox
 * (voxr_layout.h), row by row; work item i writes record r = window_begin + i: its triangle is the last t with
 * offsets[t] <= r (a binary search over the exclusive scan of the setup kernel's copy counts, so a triangle
 * with thousands of copies is expanded by as many work items), its copy q = r - offsets[t] the cell
 * (first column + q % width, first row + q / width). Only the window is written, so the host can expand and
 * consume the records in batches that fit its memory budget (host/cl/record_bins.h).
 * The window may run past the last record (a capacity the host chose without waiting for the total): it
 * ends at `total` (the scan's grand total, on the device), and work item 0 writes how many records it holds
 * to window_records, which the consumer kernel reads as its record count.
 * in:  offsets[t] (exclusive scan of the copy counts, ulong), boxes[t], total
 * out: records[i], i < min(window_count, total - window_begin); window_records
 * shape: one work item per record of the window. */
#include "voxr_layout.h"

#ifndef WG_SIZE
#define WG_SIZE 256
#endif

/* The last t in [lo, hi) with offsets[t] <= r, given offsets[lo] <= r. */
inline uint expand_find(__global const ulong* offsets, uint lo, uint hi, ulong r) {
  while (hi - lo > 1) {
    const uint mid = lo + (hi - lo) / 2;
    if (offsets[mid] <= r)
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void expand_copies(
    uint triangle_count, __global const ulong* offsets, __global const CopyBox* boxes,
    __global const ulong* total, ulong window_begin, uint window_count, __global CopyRecord* records,
    __global uint* window_records) {
  const ulong left = *total > window_begin ? *total - window_begin : 0;
  if (left < window_count) window_count = (uint)left;
  if (get_global_id(0) == 0) *window_records = window_count;
  if (triangle_count == 0 || window_count == 0) return;
  /* The group's records lie between the triangles of its first and its last record: one search over all
   * triangles per group, then each work item searches only that range (a few steps where triangles have a
   * few copies each). */
  __local uint range[2];
  const uint i = get_global_id(0);
  if (get_local_id(0) == 0) {
    const uint first = get_group_id(0) * WG_SIZE, last = min(first + WG_SIZE, window_count) - 1;
    range[0] = expand_find(offsets, 0, triangle_count, window_begin + first);
    range[1] = expand_find(offsets, range[0], triangle_count, window_begin + last);
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  if (i >= window_count) return;
  const ulong r = window_begin + i;
  const uint t = expand_find(offsets, range[0], range[1] + 1, r);
  const uint q = (uint)(r - offsets[t]);
  const CopyBox box = boxes[t];
  CopyRecord rec;
  rec.triangle = t;
  rec.cell = VOXR_CELL(VOXR_CELL_COLUMN(box.first) + q % box.width, VOXR_CELL_ROW(box.first) + q / box.width);
  records[i] = rec;
}
