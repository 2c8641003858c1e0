/* vox_solid_bits.h — bit-array helpers shared by the solid-fill stages (vox_solid_*.cl).
 *
 * The solid stages keep per-voxel bits in a row-padded layout: every x row (fixed j, k) starts on a word
 * boundary, word index k * slice_words + j * words_x + i / 32, bit i % 32, words_x = ceil(nx / 32); padding
 * bits (i >= nx) stay 0 and padding words are never read. One 32-bit word then holds 32 neighbouring
 * columns, so a work item can sweep 32 columns along z (or y) with whole-word operations and own every word
 * it writes (no atomics, deterministic). slice_words >= ny * words_x is an odd number of 64-byte lines (see
 * solid_fill.cpp): a sweep along z then visits every cache set of a CPU device instead of one, which a
 * power-of-two layer size would do.
 * The dense layout of VoxelGrid::occ / inside packs linear indices (k * ny + j) * nx + i without padding. */
#ifndef VOX_SOLID_BITS_H
#define VOX_SOLID_BITS_H

/* Mask of the low n bits, n in [0, 32] (OpenCL masks shift counts, so 1u << 32 is not 0). */
inline uint vox_low_bits(uint n) {
  return n >= 32u ? 0xffffffffu : (1u << n) - 1u;
}

/* Bits of row word wx that hold real columns (i < nx). */
inline uint vox_row_valid(uint nx, uint wx) {
  return vox_low_bits(nx - 32u * wx);
}

/* n (1..32) bits of `bits` starting at bit `offset`; every bit read must lie inside the array. */
inline uint vox_extract_bits(__global const uint* bits, ulong offset, uint n) {
  const ulong word = offset >> 5;
  const uint shift = (uint)(offset & 31);
  uint v = bits[word] >> shift;
  if (shift != 0 && n > 32u - shift) v |= bits[word + 1] << (32u - shift);
  return v & vox_low_bits(n);
}

#endif
