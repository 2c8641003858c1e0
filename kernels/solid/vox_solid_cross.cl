/* vox_solid_cross.cl — where every triangle crosses the column centre lines (i+1/2, j+1/2, z): toggles.
 * A triangle crosses column (i, j) when the centre lies in its xy projection under the pixel-centre rule of
 * vox_raster.cl (top-left tie rule, edge-on triangles excluded). That rule is a symbolic perturbation of the
 * centre to (x + e, y - e^2): the perturbed line misses every projected edge and vertex, so on a closed mesh
 * every column is crossed an even number of times, and a centre on a shared edge or vertex is counted once
 * in a consistently tiled neighbourhood (twice or never on a silhouette: even either way).
 * The crossing depth zc = v0z + D / |n_z| is exact (D is 64-bit). The voxel it toggles:
 *   VOX_SOLID_RULE 0 (parity): the first voxel whose centre lies at or above the crossing,
 *     k = min{k : k + 1/2 >= zc}. A crossing exactly at a centre counts as below it, so after the prefix
 *     XOR a voxel is inside iff an odd number of crossings lie at or below its centre.
 *   VOX_SOLID_RULE 1 (xor): the voxel whose slab [k, k+1) holds the crossing (the centre-mode surface
 *     voxel, XOR-blended), k = floor(zc).
 * Crossings below the grid toggle voxel 0, crossings above it toggle nothing. VOX_SOLID_ODD also flips the
 * column's bit in `odd` for every crossing, in the grid or not (the late mode's crossing-count parity).
 * Float only narrows each row's column range (with a margin far above its error); membership and depth are
 * exact integer tests.
 * in:  snapped triangles, item_counts and item_offsets (exclusive scan) from vox_solid_setup.cl
 * out: toggles (row-padded bits, vox_solid_bits.h; one atomic_xor per run of a row's centres that share a
 *      word and a voxel layer), odd (one row-padded bit per column, atomic_xor)
 * shape: one work item per (triangle, block of VOX_SOLID_ROWS rows); the item finds its triangle by binary
 *        search of item_offsets. A launch runs items [item_base, item_base + global size) of item_total. */
#include "voxr_layout.h"

#undef VOXR_MODE
#define VOXR_MODE VOXR_MODE_CENTER
#include "vox_triangle.h"

#ifndef WG_SIZE
#define WG_SIZE 64
#endif
#ifndef VOX_SOLID_ROWS
#define VOX_SOLID_ROWS 4
#endif
#ifndef VOX_SOLID_RULE
#define VOX_SOLID_RULE 0
#endif
#ifndef VOX_SOLID_ODD
#define VOX_SOLID_ODD 0
#endif
/* Margin (fixed-point units) of the float column range of a row. */
#define VOX_SOLID_MARGIN (VOX_S / 16)

typedef struct VoxFlush {
  ulong word;
  uint mask;
} VoxFlush;

inline void vox_flush_xor(__global uint* bits, VoxFlush* f) {
  if (f->mask) atomic_xor(bits + f->word, f->mask);
  f->mask = 0;
}

inline void vox_toggle(__global uint* bits, VoxFlush* f, ulong word, uint bit) {
  if (word != f->word) {
    vox_flush_xor(bits, f);
    f->word = word;
  }
  f->mask ^= bit;
}

/* The voxel the crossing at relative depth D / an (an = |n_z| > 0, D = an * (zc - v0z)) toggles. The float
 * estimate is corrected by exact tests; every product stays within the triangle's extent times an. */
inline long vox_crossing_voxel(long D, long an, long v0z) {
  const float est = ((float)v0z + (float)D / (float)an) / (float)VOX_S;
#if VOX_SOLID_RULE == 0
  /* smallest k with (k*S + S/2 - v0z) * an >= D */
  long k = (long)ceil(est - 0.5f);
  while ((k * VOX_S + VOX_S / 2 - v0z) * an < D) ++k;
  while (((k - 1) * VOX_S + VOX_S / 2 - v0z) * an >= D) --k;
#else
  /* largest k with (k*S - v0z) * an <= D */
  long k = (long)floor(est);
  while ((k * VOX_S - v0z) * an > D) --k;
  while (((k + 1) * VOX_S - v0z) * an <= D) ++k;
#endif
  return k;
}

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void vox_solid_cross(
    VoxGridParams grid, __global const VoxSnappedTriangle* snapped, __global const uint* item_counts,
    __global const ulong* item_offsets, ulong item_base, ulong item_total, VoxSolidLayout layout,
    __global uint* toggles, __global uint* odd) {
  const uint words_x = layout.words_x, slice_words = layout.slice_words;
  const ulong item = item_base + get_global_id(0);
  if (item >= item_total) return;
  /* The triangle owning the item: the last one whose offset is <= item (empty triangles share the offset of
   * the next non-empty one and come before it). */
  uint lo = 0, hi = grid.triangle_count - 1;
  while (lo < hi) {
    const uint mid = hi - (hi - lo) / 2;
    if (item_offsets[mid] <= item)
      lo = mid;
    else
      hi = mid - 1;
  }
  const uint block = (uint)(item - item_offsets[lo]);

  VoxTri t;
  vox_fetch_triangle(&t, snapped, lo);
  vox_derive(&t, &grid);
  const int row_first = t.first[1] + (int)block * VOX_SOLID_ROWS;
  const int row_last = min(t.last[1], row_first + VOX_SOLID_ROWS - 1);

  VoxCoverage coverage; /* the centre rule, shared with vox_scanline.h */
  vox_coverage_init(&coverage, &t);
  const long sgn = t.n[2] > 0 ? 1 : -1;
  const long an = sgn * t.n[2];
  const long v0z = t.v[0][2];
  const uint nz = grid.dims[2];

  VoxFlush tog, par;
  tog.word = par.word = ~0UL;
  tog.mask = par.mask = 0;

  for (int j = row_first; j <= row_last; ++j) {
    const long cy = (long)j * VOX_S + VOX_S / 2;
    /* Narrow the columns to the projection's extent along this row (float, superset). */
    float xlo = INFINITY, xhi = -INFINITY;
    for (int e = 0; e < 3; ++e) {
      const int f = e == 2 ? 0 : e + 1;
      const long ya = coverage.py[e], yb = coverage.py[f];
      if (min(ya, yb) > cy || max(ya, yb) < cy) continue;
      float xa = (float)coverage.px[e], xb = (float)coverage.px[f];
      if (ya != yb) xa = xb = xa + (xb - xa) * ((float)(cy - ya) / (float)(yb - ya));
      xlo = fmin(xlo, fmin(xa, xb));
      xhi = fmax(xhi, fmax(xa, xb));
    }
    if (!(xlo <= xhi)) continue;
    const int col_first = max(t.first[0], (int)ceil((xlo - VOX_SOLID_MARGIN) / (float)VOX_S - 0.5f));
    const int col_last = min(t.last[0], (int)floor((xhi + VOX_SOLID_MARGIN) / (float)VOX_S - 0.5f));
    if (col_first > col_last) continue;

    const long cx0 = (long)col_first * VOX_S + VOX_S / 2;
    long edge[3];
    vox_coverage_start(&coverage, col_first, j, edge);
    long depth = -sgn * (t.n[0] * (cx0 - t.v[0][0]) + t.n[1] * (cy - t.v[0][1]));
    const long depth_step = -sgn * t.n[0] * VOX_S;
    for (int i = col_first; i <= col_last; ++i) {
      const int inside = vox_coverage_next(&coverage, edge);
      if (inside) {
        const uint bit = 1u << (i & 31);
#if VOX_SOLID_ODD
        vox_toggle(odd, &par, (ulong)j * words_x + (uint)(i >> 5), bit);
#endif
        const long k = max(vox_crossing_voxel(depth, an, v0z), 0L);
        if (k < (long)nz)
          vox_toggle(toggles, &tog, (ulong)k * slice_words + (ulong)j * words_x + (uint)(i >> 5), bit);
      }
      depth += depth_step;
    }
  }
  vox_flush_xor(toggles, &tog);
#if VOX_SOLID_ODD
  vox_flush_xor(odd, &par);
#endif
}
