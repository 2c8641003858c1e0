/* vox_solid_unpack.cl — row-padded bits (vox_solid_bits.h) to the dense layout of VoxelGrid::inside
 * (linear index (k * ny + j) * nx + i, 32 per word, no padding; bits past the last voxel stay 0).
 * VOX_SOLID_INVERT writes the complement (the flood fill's inside = not outside).
 * in:  padded (row-padded bits)
 * out: dense (dense bits)
 * shape: one work item per x row (j, k), writing the dense words whose first voxel lies in its row (none for
 *        some rows when nx < 32); a word reaching into the next rows is gathered row piece by row piece. */
#include "voxr_layout.h"
#include "vox_solid_bits.h"

#ifndef WG_SIZE
#define WG_SIZE 64
#endif
#ifndef VOX_SOLID_INVERT
#define VOX_SOLID_INVERT 0
#endif

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void vox_solid_unpack(
    VoxSolidLayout layout, __global const uint* padded,
    __global uint* dense) {
  const uint nx = layout.dims[0], ny = layout.dims[1], nz = layout.dims[2];
  const uint words_x = layout.words_x, slice_words = layout.slice_words;
  const uint row = get_global_id(0);
  if (row >= ny * nz) return;
  const ulong voxels = (ulong)nx * ny * nz;
  const ulong start = (ulong)row * nx;
  const ulong word_end = (min(start + nx, voxels) + 31) / 32;
  const uint row_k = row / ny, row_j = row - row_k * ny;
  for (ulong word = (start + 31) / 32; word < word_end; ++word) {
    ulong linear = word * 32;
    const ulong end = min(linear + 32, voxels);
    uint k = row_k, j = row_j, i = (uint)(linear - start);
    uint out = 0, pos = 0;
    while (linear < end) {
      const uint n = (uint)min((ulong)(nx - i), end - linear);
      uint v = vox_extract_bits(padded, ((ulong)k * slice_words + (ulong)j * words_x) * 32 + i, n);
#if VOX_SOLID_INVERT
      v = ~v & vox_low_bits(n);
#endif
      out |= v << pos;
      pos += n;
      linear += n;
      i = 0;
      if (++j == ny) {
        j = 0;
        ++k;
      }
    }
    dense[word] = out;
  }
}
