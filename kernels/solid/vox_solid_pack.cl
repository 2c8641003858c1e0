/* vox_solid_pack.cl — the flood fill's start: the surface occupancy (dense bits, VoxelGrid::occ layout) to
 * row-padded free-space bits, and the seeds of the outside: every free voxel on the grid's border.
 * in:  surface (dense bits, (k * ny + j) * nx + i)
 * out: free_bits = real voxels that are not surface, outside = free border voxels (both row-padded,
 *      vox_solid_bits.h; padding words are left alone, no stage reads them)
 * shape: one work item per x row (j, k), its words_x words in turn. */
#include "voxr_layout.h"
#include "vox_solid_bits.h"

#ifndef WG_SIZE
#define WG_SIZE 64
#endif

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void vox_solid_pack(
    VoxSolidLayout layout, __global const uint* surface,
    __global uint* free_bits, __global uint* outside) {
  const uint nx = layout.dims[0], ny = layout.dims[1], nz = layout.dims[2];
  const uint words_x = layout.words_x, slice_words = layout.slice_words;
  const uint row = get_global_id(0);
  if (row >= ny * nz) return;
  const uint k = row / ny, j = row - k * ny;
  const int face = j == 0 || j + 1 == ny || k == 0 || k + 1 == nz;
  const ulong base = (ulong)k * slice_words + (ulong)j * words_x;
  for (uint wx = 0; wx < words_x; ++wx) {
    const uint n = min(32u, nx - 32u * wx);
    const uint f = ~vox_extract_bits(surface, (ulong)row * nx + 32u * wx, n) & vox_low_bits(n);
    uint border = face ? 0xffffffffu : 0u;
    if (wx == 0) border |= 1u;
    if (wx == (nx - 1) / 32) border |= 1u << ((nx - 1) & 31);
    free_bits[base + wx] = f;
    outside[base + wx] = f & border;
  }
}
