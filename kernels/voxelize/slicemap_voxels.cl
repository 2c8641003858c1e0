/* slicemap_voxels.cl — slicemap stage 4: turn the column bit masks into the voxel grid. Voxel (i, j, k) is
 * set iff a set bit of column (i, j) holds a fixed-point depth in [k S, (k+1) S):
 *   SLICEMAP_LOCAL 0 (uniform): bit b is voxel b;
 *   SLICEMAP_LOCAL 1: bit b holds depths [near + ceil(b W / B), near + ceil((b+1) W / B)), with
 *                     W = far - near + 1 and B = dims.z; W <= B S, so that is one voxel or two neighbours.
 * in:  slicemap (slicemap_raster.cl pass 1), depth_range (local: slicemap_raster.cl pass 0)
 * out: occ (zero-filled; atomic_or, linear voxel index (k dims.y + j) dims.x + i, 64-bit)
 * shape: one work item per slicemap word (column, word). */
#include "voxr_layout.h"

#ifndef WG_SIZE
#define WG_SIZE 256
#endif
#ifndef SLICEMAP_LOCAL
#define SLICEMAP_LOCAL 0
#endif

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void slicemap_voxels(
    VoxGridParams grid, __global const uint* slicemap, __global const uint* depth_range, __global uint* occ) {
  const ulong gid = get_global_id(0);
  const ulong dims_x = grid.dims[0], dims_y = grid.dims[1], slices = grid.dims[2];
  const ulong words_per_column = (slices + 31) / 32;
  if (gid >= dims_x * dims_y * words_per_column) return;
  uint bits = slicemap[gid];
  if (bits == 0) return;
  const ulong column = gid / words_per_column;
  const ulong word = gid - column * words_per_column;
  const ulong i = column % dims_x, j = column / dims_x;
#if SLICEMAP_LOCAL
  const ulong z_end = slices * VOXR_SUBVOXEL;
  const ulong near = z_end - depth_range[2 * column];
  const ulong width = depth_range[2 * column + 1] - near; /* far + 1 - near */
#endif
  while (bits) {
    const uint low = bits & (~bits + 1u);
    bits ^= low;
    const ulong b = word * 32 + (31 - clz(low));
#if SLICEMAP_LOCAL
    const ulong begin = near + (b * width + slices - 1) / slices;     /* first depth of the bit */
    const ulong end = near + ((b + 1) * width + slices - 1) / slices; /* one past the last */
    if (begin >= end) continue; /* an empty bit is never set; guard anyway */
    const ulong k_first = begin >> VOXR_SUBVOXEL_BITS;
    const ulong k_last = min((end - 1) >> VOXR_SUBVOXEL_BITS, slices - 1);
#else
    const ulong k_first = b, k_last = min(b, slices - 1);
#endif
    for (ulong k = k_first; k <= k_last; ++k) {
      const ulong linear = (k * dims_y + j) * dims_x + i;
      atomic_or(occ + (linear >> 5), 1u << (uint)(linear & 31));
    }
  }
}
