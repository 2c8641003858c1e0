/* vox_solid_repair.cl — one round of the late mode's repair of questionable columns (TR 1688, Fig. 3).
 * A questionable column that is still unresolved and has at least one resolved 4-neighbour (i±1, j±1)
 * takes, voxel by voxel, the majority of its resolved neighbours' inside values; a tie counts as inside (with
 * m resolved neighbours the voxel is inside when at least ceil(m/2) of them are). The column is then
 * resolved. Rounds are Jacobi steps: only neighbours resolved before this round vote (resolved_in), new
 * resolutions go to resolved_out, so the result does not depend on the order work items run in. The host
 * repeats rounds until one changes nothing; columns with no resolved column in reach stay empty.
 * in:  inside (row-padded bits, vox_solid_bits.h; unresolved columns all 0), resolved_in (row-padded column
 *      bits)
 * out: inside (bits of the newly resolved columns of the item's own words), resolved_out, changed = 1 when a
 *      column was resolved
 * shape: one work item per row word (j, wx): 32 columns, every layer k, whole-word operations. An item writes
 *        only its own words, and the bits other items read from them (resolved_in columns) do not change. */
#include "voxr_layout.h"
#include "vox_solid_bits.h"

#ifndef WG_SIZE
#define WG_SIZE 64
#endif

/* Bits set in at least two of a, b, c, d. */
inline uint vox_at_least_two(uint a, uint b, uint c, uint d) {
  return (a & b) | (c & d) | ((a | b) & (c | d));
}

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void vox_solid_repair(
    VoxSolidLayout layout, __global uint* inside,
    __global const uint* resolved_in, __global uint* resolved_out, __global uint* changed) {
  const uint nx = layout.dims[0], ny = layout.dims[1], nz = layout.dims[2];
  const uint words_x = layout.words_x, slice_words = layout.slice_words;
  const uint gid = get_global_id(0);
  if (gid >= ny * words_x) return;
  const uint j = gid / words_x, wx = gid - j * words_x;
  const uint r = resolved_in[gid];
  const uint open = vox_row_valid(nx, wx) & ~r;
  /* Resolved neighbours, aligned to this word's columns: left = column i-1, right = i+1, down = j-1, up =
   * j+1. */
  const uint r_left = (r << 1) | (wx > 0 ? resolved_in[gid - 1] >> 31 : 0u);
  const uint r_right = (r >> 1) | (wx + 1 < words_x ? resolved_in[gid + 1] << 31 : 0u);
  const uint r_down = j > 0 ? resolved_in[gid - words_x] : 0u;
  const uint r_up = j + 1 < ny ? resolved_in[gid + words_x] : 0u;
  const uint fresh = open & (r_left | r_right | r_down | r_up);
  resolved_out[gid] = r | fresh;
  if (!fresh) return;
  *changed = 1u; /* every writer stores the same value */

  /* With three or four voters the majority needs two, with one or two a single inside vote wins. */
  const uint three = (r_left & r_right & (r_down | r_up)) | (r_down & r_up & (r_left | r_right));
  for (uint k = 0; k < nz; ++k) {
    const ulong w = (ulong)k * slice_words + gid;
    const uint v = inside[w];
    const uint left = ((v << 1) | (wx > 0 ? inside[w - 1] >> 31 : 0u)) & r_left;
    const uint right = ((v >> 1) | (wx + 1 < words_x ? inside[w + 1] << 31 : 0u)) & r_right;
    const uint down = j > 0 ? inside[w - words_x] & r_down : 0u;
    const uint up = j + 1 < ny ? inside[w + words_x] & r_up : 0u;
    const uint one = left | right | down | up;
    const uint two = vox_at_least_two(left, right, down, up);
    const uint set = fresh & ((three & two) | (~three & one));
    if (set) inside[w] = v | set;
  }
}
