/* scan.cl — exclusive prefix sum of any length, in three steps driven by host/cl/scan.cpp:
 * scan_tiles scans tiles of WG_SIZE*SCAN_ITEMS elements and writes each tile's total; the host scans the
 * totals recursively; scan_add adds each tile's offset.
 * Types: SCAN_IN (uint or ulong) is read, SCAN_OUT is written, tile totals are ulong so a grand total
 * beyond 32 bits is still exact. SCAN_RANKED_WORDS scans the set-bit counts of 32-bit occupancy words and
 * writes each word beside its rank (the rank index, voxr_layout.h VOXR_RANKED), so a voxel's rank costs one load.
 * shape: scan_tiles one work group per tile; scan_add one work item per SCAN_ITEMS elements. */
#include "voxr_layout.h"

#ifndef WG_SIZE
#define WG_SIZE 256
#endif
#ifndef SCAN_ITEMS
#define SCAN_ITEMS 8
#endif
#ifndef SCAN_IN
#define SCAN_IN uint
#endif
#ifndef SCAN_OUT
#define SCAN_OUT ulong
#endif
#ifdef SCAN_RANKED_WORDS
#define SCAN_LOAD(x) ((ulong)popcount(x))
#define SCAN_STORE(i, rank) (out[i] = VOXR_RANKED(rank, in[i]))
#define SCAN_SHIFT 32
#else
#define SCAN_LOAD(x) ((ulong)(x))
#define SCAN_STORE(i, sum) (out[i] = (SCAN_OUT)(sum))
#define SCAN_SHIFT 0
#endif

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void scan_tiles(
    __global const SCAN_IN* in, __global SCAN_OUT* out, __global ulong* tile_sums, ulong n) {
  __local ulong partial[WG_SIZE];
  const uint lid = get_local_id(0);
  const ulong base = ((ulong)get_group_id(0) * WG_SIZE + lid) * SCAN_ITEMS;
  ulong prefix[SCAN_ITEMS];
  ulong sum = 0;
  for (int q = 0; q < SCAN_ITEMS; ++q) {
    prefix[q] = sum;
    sum += base + q < n ? SCAN_LOAD(in[base + q]) : 0;
  }
  partial[lid] = sum;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint offset = 1; offset < WG_SIZE; offset <<= 1) {
    const ulong add = lid >= offset ? partial[lid - offset] : 0;
    barrier(CLK_LOCAL_MEM_FENCE);
    partial[lid] += add;
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  const ulong before = lid > 0 ? partial[lid - 1] : 0;
  for (int q = 0; q < SCAN_ITEMS; ++q)
    if (base + q < n) SCAN_STORE(base + q, before + prefix[q]);
  if (lid == WG_SIZE - 1) tile_sums[get_group_id(0)] = partial[lid];
}

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void scan_add(
    __global SCAN_OUT* out, __global const ulong* tile_offsets, ulong n) {
  const ulong base = (ulong)get_global_id(0) * SCAN_ITEMS;
  const SCAN_OUT offset = (SCAN_OUT)(tile_offsets[get_group_id(0)] << SCAN_SHIFT);
  for (int q = 0; q < SCAN_ITEMS; ++q)
    if (base + q < n) out[base + q] += offset;
}
