/* vox_solid_flood.cl — one sweep of the flood fill of the outside: along every line of one axis, forward
 * then backward, a free voxel next to an outside voxel becomes outside. The host runs the x, y and z sweeps
 * in turn until a round changes nothing. A round follows at least one straight segment of any path (usually
 * three or more), so a path of s segments is flooded within s rounds; mazes are the slow case.
 * The outside only grows and each sweep kernel reads and writes only its own lines, so the result (the free
 * voxels 6-connected to a free border voxel) and the number of rounds are independent of scheduling.
 * in:  free_bits (real non-surface voxels), outside (row-padded bits, vox_solid_bits.h)
 * out: outside, grown in place; changed = 1 when a sweep grew it
 * shape: vox_solid_flood_x: one work item per row (j, k), 32 voxels per step with a log-step fill inside the
 *        word; vox_solid_flood_y / _z: one work item per row word, 32 parallel lines along y / z. */
#include "voxr_layout.h"
#include "vox_solid_bits.h"

#ifndef WG_SIZE
#define WG_SIZE 64
#endif

/* Spreads g towards higher bits through runs of p (occluded fill, Kogge-Stone); g is a subset of p. */
inline uint vox_fill_up(uint g, uint p) {
  if (g == 0 || g == p) return g; /* nothing to spread (most words: all outside or none) */
  g |= p & (g << 1);
  p &= p << 1;
  g |= p & (g << 2);
  p &= p << 2;
  g |= p & (g << 4);
  p &= p << 4;
  g |= p & (g << 8);
  p &= p << 8;
  return g | (p & (g << 16));
}

inline uint vox_fill_down(uint g, uint p) {
  if (g == 0 || g == p) return g;
  g |= p & (g >> 1);
  p &= p >> 1;
  g |= p & (g >> 2);
  p &= p >> 2;
  g |= p & (g >> 4);
  p &= p >> 4;
  g |= p & (g >> 8);
  p &= p >> 8;
  return g | (p & (g >> 16));
}

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void vox_solid_flood_x(
    VoxSolidLayout layout, __global const uint* free_bits, __global uint* outside,
    __global uint* changed) {
  const uint ny = layout.dims[1], nz = layout.dims[2];
  const uint words_x = layout.words_x, slice_words = layout.slice_words;
  const ulong row = get_global_id(0);
  if (row >= (ulong)ny * nz) return;
  const ulong k = row / ny;
  const ulong base = k * slice_words + (row - k * ny) * words_x;
  uint grown = 0;
  uint carry = 0; /* 1 when the previous voxel of the sweep is outside */
  for (uint wx = 0; wx < words_x; ++wx) {
    const uint f = free_bits[base + wx], o = outside[base + wx];
    const uint g = vox_fill_up(o | (carry & f), f);
    if (g != o) outside[base + wx] = g;
    grown |= g ^ o;
    carry = g >> 31;
  }
  carry = 0;
  for (uint wx = words_x; wx-- > 0;) {
    const uint f = free_bits[base + wx], o = outside[base + wx];
    const uint g = vox_fill_down(o | ((carry << 31) & f), f);
    if (g != o) outside[base + wx] = g;
    grown |= g ^ o;
    carry = g & 1u;
  }
  if (grown) *changed = 1u;
}

/* 32 lines along an axis whose consecutive voxels are `stride` words apart. */
inline uint vox_sweep_lines(__global const uint* free_bits, __global uint* outside, ulong first, ulong stride,
                            uint count) {
  uint grown = 0, prev = 0;
  for (uint q = 0; q < count; ++q) {
    const ulong w = first + q * stride;
    const uint f = free_bits[w], o = outside[w];
    const uint g = o | (prev & f);
    if (g != o) outside[w] = g;
    grown |= g ^ o;
    prev = g;
  }
  prev = 0;
  for (uint q = count; q-- > 0;) {
    const ulong w = first + q * stride;
    const uint f = free_bits[w], o = outside[w];
    const uint g = o | (prev & f);
    if (g != o) outside[w] = g;
    grown |= g ^ o;
    prev = g;
  }
  return grown;
}

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void vox_solid_flood_y(
    VoxSolidLayout layout, __global const uint* free_bits, __global uint* outside,
    __global uint* changed) {
  const uint ny = layout.dims[1], nz = layout.dims[2];
  const uint words_x = layout.words_x, slice_words = layout.slice_words;
  const ulong gid = get_global_id(0);
  if (gid >= (ulong)nz * words_x) return;
  const ulong k = gid / words_x, wx = gid - k * words_x;
  if (vox_sweep_lines(free_bits, outside, k * slice_words + wx, words_x, ny)) *changed = 1u;
}

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void vox_solid_flood_z(
    VoxSolidLayout layout, __global const uint* free_bits, __global uint* outside,
    __global uint* changed) {
  const uint ny = layout.dims[1], nz = layout.dims[2];
  const uint words_x = layout.words_x, slice_words = layout.slice_words;
  const ulong gid = get_global_id(0);
  if (gid >= (ulong)ny * words_x) return;
  if (vox_sweep_lines(free_bits, outside, gid, slice_words, nz)) *changed = 1u;
}
