/* vox_solid_prefix.cl — prefix XOR of the crossing toggles along every column: afterwards bit (i, j, k) is
 * the XOR of the toggles at (i, j, 0..k), the parity of the crossings before voxel k's centre (or slab top).
 * VOX_SOLID_LATE also sorts the columns by the parity of their crossing count (`odd`, vox_solid_cross.cl):
 * even columns are resolved, their parity fill stands; odd ones are "questionable": counted, their bits
 * cleared, and filled from their neighbours by vox_solid_repair.cl.
 * in:  toggles (row-padded bits, vox_solid_bits.h), odd (one row-padded bit per column; late only)
 * out: toggles, in place; resolved (one row-padded bit per column; late only); questionable += odd columns
 * shape: one work item per row word (j, wx), sweeping 32 columns along z at once. */
#include "voxr_layout.h"
#include "vox_solid_bits.h"

#ifndef WG_SIZE
#define WG_SIZE 64
#endif
#ifndef VOX_SOLID_LATE
#define VOX_SOLID_LATE 0
#endif

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void vox_solid_prefix(
    VoxSolidLayout layout, __global uint* toggles,
    __global const uint* odd, __global uint* resolved, __global uint* questionable) {
  const uint nx = layout.dims[0], ny = layout.dims[1], nz = layout.dims[2];
  const uint words_x = layout.words_x, slice_words = layout.slice_words;
  const uint gid = get_global_id(0);
  if (gid >= ny * words_x) return;
  const uint j = gid / words_x, wx = gid - j * words_x;
  uint keep = vox_row_valid(nx, wx);
#if VOX_SOLID_LATE
  const uint bad = odd[gid] & keep;
  keep &= ~bad;
  resolved[gid] = keep;
  if (bad) atomic_add(questionable, popcount(bad));
#endif
  uint acc = 0;
  for (uint k = 0; k < nz; ++k) {
    const ulong w = (ulong)k * slice_words + gid;
    acc ^= toggles[w];
    toggles[w] = acc & keep;
  }
}
