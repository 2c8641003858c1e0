/* vox_scanline.h — the scanline work of one triangle copy, shared by vox_raster.cl (one work item per
 * copy record: the papers' method) and vox_grid.cl (one launch per slab over every triangle: the "Grid"
 * baseline), so both produce the same voxels by construction.
 *   conservative: voxel box (closed) overlaps the closed triangle — the 13-axis separating-axis test,
 *                 evaluated incrementally along each row in exact 64-bit integers;
 *   center:       the column centre (i+1/2, j+1/2) lies inside the triangle's projection (top-left tie
 *                 rule) and the triangle's depth there lies in the slab [k, k+1).
 * Float clipping of the triangle against the slab and each row only narrows the candidate range (with a
 * margin far above float error); membership is always decided by the exact integer test.
 * VOX_PASS 0 sets occupancy bits (one atomic_or per 32 voxels of a row). VOX_PASS 1 runs after the ranks
 * of set voxels are known and adds the attributes that VoxGridParams.channels asks for (VOX_CH_COUNT,
 * VOX_CH_NORMAL: sum, VOX_CH_MATERIAL; a runtime mask, so one program serves every subset) at each voxel's
 * rank. Count and normal sum share two 64-bit accumulators per voxel so a write
 * costs two atomics, not four: acc[2r] += n.x + 2^32 (count in the high half), acc[2r+1] += n.y + n.z*2^32.
 * Two's complement makes the packed sums exact; vox_finalize.cl unpacks them. VOX_CH_COLOR also counts
 * there (the colour's mean divides by the count) and adds the triangle's colour at the voxel's centre
 * (vox_color.h) to two more 64-bit sums per voxel, color_acc[2r] += R + G 2^32, color_acc[2r+1] += B + A 2^32.
 * VOX_PASS 2 (triangle lists, after count -> scan) visits the same (triangle, voxel) pairs as pass 1 and
 * appends the triangle's mesh index to the voxel's list: `acc` is then a 64-bit cursor per rank, started at
 * the list's offset, and `material` the id array (VoxGridParams.list_capacity entries). */
#ifndef VOX_SCANLINE_H
#define VOX_SCANLINE_H

#include "voxr_layout.h"
#include "vox_triangle.h"
#include "vox_color.h"

#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable

#ifndef VOX_PASS
#define VOX_PASS 0
#endif
/* VOX_SPARSE 1: the grid is stored in 8^3 bricks (host/grid/sparse_voxel_grid.h): the kernels still walk
 * voxels by their cell (i, j, k) in the grid (a window of slices, VoxGridParams.first_slice), and
 * vox_emit maps it to the voxel's bit in its brick's slot: slot * 512 + x + 8 y + 64 z within the brick. The
 * slots come from `bricks`, the rank index (VOXR_RANKED) of the window's brick occupancy, one bit per brick
 * in linear brick order (the coarse pass, host/voxelize/sparse_voxelizer.h, marks every brick a voxel can be
 * set in). A voxel whose brick is not marked sets the flag word after the rank index and is dropped. */
#ifndef VOX_SPARSE
#define VOX_SPARSE 0
#endif
/* Triangles spanning fewer than this many cells per axis skip the float clipping. */
#ifndef VOX_SMALL_SPAN
#define VOX_SMALL_SPAN 3
#endif
#define VOX_CLIP_MARGIN 0.0625f

/* The channel bits VOX_CH_* come from the channel table (host/grid/channel_table.h). */
#if VOX_PASS >= 1 && !defined(VOX_CH_COUNT)
#error "pass 1 needs the channel defines of host/grid/channel_table.h"
#endif

/* ---- float clipping: candidate ranges only ---------------------------------------------------------- */

typedef struct VoxPoly {
  float c[3][8]; /* c[axis][vertex] */
  int n;
} VoxPoly;

/* Keeps the part of `in` where sign * (x_axis - bound) >= 0. */
inline void vox_clip(VoxPoly* out, const VoxPoly* in, int axis, float bound, float sign) {
  out->n = 0;
  for (int a = 0; a < in->n; ++a) {
    const int b = a + 1 == in->n ? 0 : a + 1;
    const float da = sign * (in->c[axis][a] - bound);
    const float db = sign * (in->c[axis][b] - bound);
    if (da >= 0.0f) {
      for (int q = 0; q < 3; ++q) out->c[q][out->n] = in->c[q][a];
      ++out->n;
    }
    if ((da >= 0.0f) != (db >= 0.0f)) {
      const float s = da / (da - db);
      for (int q = 0; q < 3; ++q) out->c[q][out->n] = in->c[q][a] + s * (in->c[q][b] - in->c[q][a]);
      ++out->n;
    }
  }
}

inline void vox_clip_band(VoxPoly* poly, int axis, float lo, float hi) {
  VoxPoly tmp;
  vox_clip(&tmp, poly, axis, lo, 1.0f);
  vox_clip(poly, &tmp, axis, hi, -1.0f);
}

inline void vox_poly_range(const VoxPoly* poly, int axis, float* lo, float* hi) {
  *lo = INFINITY;
  *hi = -INFINITY;
  for (int a = 0; a < poly->n; ++a) {
    *lo = fmin(*lo, poly->c[axis][a]);
    *hi = fmax(*hi, poly->c[axis][a]);
  }
}

/* Cells whose raster sample meets [lo, hi] along an axis (a superset thanks to the padding `pad`). */
inline void vox_cells(float lo, float hi, float pad, int* first, int* last) {
  lo -= pad;
  hi += pad;
#if VOXR_MODE == VOXR_MODE_CONSERVATIVE
  *first = (int)ceil(lo) - 1;
  *last = (int)floor(hi);
#else
  *first = (int)ceil(lo - 0.5f);
  *last = (int)floor(hi - 0.5f);
#endif
}

/* ---- voxel writes -------------------------------------------------------------------------------- */

typedef struct VoxWriter {
  __global uint* occ;
  __global const ulong* ranked; /* pass 1: the rank index (voxr_layout.h VOXR_RANKED) */
  __global long* acc;     /* pass 2: the list cursors */
  __global uint* material; /* pass 2: the list ids */
  ulong word;        /* pass 0: the word being collected; passes 1, 2: the word of word_ranked */
  uint mask;
  ulong word_ranked; /* pass 1: ranked[word] */
  int3 normal; /* pass 1: the triangle's fixed-point unit normal (vox_fixed_normal) */
  uint material_id; /* pass 2: the triangle's mesh index, the id the lists hold */
  uint channels; /* pass 1: the channels to accumulate */
  uint entries;  /* passes 1, 2: ranks below it have accumulator and material entries (VoxGridParams.dims[3]) */
  uint list_capacity; /* pass 2: entries of the id array */
  const VoxGridParams* grid;    /* pass 1 colour: the voxel centres */
  __global long* color_acc;     /* pass 1 colour: the colour sums */
  __global const uint* texels;  /* pass 1 colour: the texture atlas */
  VoxColorTri color;            /* pass 1 colour: the triangle's colour inputs */
#if VOX_SPARSE
  __global ulong* bricks; /* the brick table, then the missing-brick flag at [brick_words] */
  ulong brick_words;
  uint bdx, bdy;          /* bricks along x and y */
  ulong brick, slot;      /* the current brick and its slot (~0: not marked) */
#endif
} VoxWriter;

/* The colour channel's kernel parameters, after the others (host: ColorArgs in slice_voxelizer.cpp). */
#define VOX_COLOR_PARAMS                                                                                   \
  VoxColorParams color, __global const uint *vertex_rgba, __global const float *vertex_uv,                 \
      __global const uint *triangle_look, __global const VoxColorLook *looks, __global const uint *texels, \
      __global long *color_acc

inline void vox_flush(VoxWriter* w) {
#if VOX_PASS == 0
  /* Most surface voxels are set by several copies: a plain read skips the locked write when the bits are
   * already there (bits are only ever set during this pass, so the race is benign). */
  if (w->mask && (w->occ[w->word] & w->mask) != w->mask) atomic_or(w->occ + w->word, w->mask);
  w->mask = 0;
#endif
}

/* Voxel (i, j, k), at linear index `linear`, is written by the writer's triangle. */
inline void vox_emit(VoxWriter* w, ulong linear, int i, int j, int k) {
#if VOX_SPARSE
  const ulong lb = ((ulong)(k >> 3) * w->bdy + (ulong)(j >> 3)) * w->bdx + (ulong)(i >> 3);
  if (lb != w->brick) { /* voxels along a row share their brick */
    w->brick = lb;
    const ulong r = w->bricks[lb >> 5];
    const uint b = 1u << (uint)(lb & 31);
    w->slot = (VOXR_RANKED_BITS(r) & b) ? (ulong)VOXR_RANKED_RANK(r) + popcount(VOXR_RANKED_BITS(r) & (b - 1u)) : ~0UL;
    if (w->slot == ~0UL) atomic_or((__global uint*)(w->bricks + w->brick_words), 1u);
  }
  if (w->slot == ~0UL) return;
  linear = w->slot * 512 + (ulong)((i & 7) + 8 * (j & 7) + 64 * (k & 7));
#endif
  const ulong word = linear >> 5;
  const uint bit = 1u << (uint)(linear & 31);
#if VOX_PASS == 0
  if (word != w->word) {
    vox_flush(w);
    w->word = word;
  }
  w->mask |= bit;
#else
  if (word != w->word) { /* voxels along a row share their ranked word */
    w->word = word;
    w->word_ranked = w->ranked[word];
  }
  const ulong rank = VOXR_RANKED_RANK(w->word_ranked) + popcount(VOXR_RANKED_BITS(w->word_ranked) & (bit - 1u));
  if (rank >= w->entries) return;
#if VOX_PASS == 2
  const ulong slot = (ulong)atom_inc(w->acc + rank);
  if (slot < w->list_capacity) w->material[slot] = w->material_id;
  return;
#endif
  if (w->channels & (VOX_CH_COUNT | VOX_CH_NORMAL | VOX_CH_COLOR))
    atom_add(w->acc + 2 * rank, (long)w->normal.x + (1L << 32));
  /* A multiplication, not a shift: shifting a negative value left is undefined in OpenCL C. */
  if (w->channels & VOX_CH_NORMAL)
    atom_add(w->acc + 2 * rank + 1, (long)w->normal.y + (long)w->normal.z * (1L << 32));
  if (w->channels & VOX_CH_MATERIAL) atomic_max(w->material + rank, w->material_id);
  if (w->channels & VOX_CH_COLOR) {
    const uint rgba = vox_color_sample(&w->color, vox_voxel_centre(w->grid, i, j, k), w->texels);
    atom_add(w->color_acc + 2 * rank, (long)(rgba & 255u) + (long)((rgba >> 8) & 255u) * (1L << 32));
    atom_add(w->color_acc + 2 * rank + 1, (long)((rgba >> 16) & 255u) + (long)(rgba >> 24) * (1L << 32));
  }
#endif
}

/* The triangle's unit normal in fixed point from n = (v1-v0) x (v2-v0); float operations in an order the
 * host reproduces (host/voxelize/snapped_triangle.cpp). */
inline void vox_fixed_normal(long3 n, int3* out) {
  const float fx = convert_float(n.x), fy = convert_float(n.y), fz = convert_float(n.z);
  const float len2 = (fx * fx + fy * fy) + fz * fz;
  const float scale = len2 > 0.0f ? (float)VOXR_NORMAL_ONE / sqrt(len2) : 0.0f;
  *out = (int3)((int)vox_rint(fx * scale), (int)vox_rint(fy * scale), (int)vox_rint(fz * scale));
}

inline long3 vox_cross(long3 a, long3 b) {
  return (long3)(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

inline long3 vox_tri_normal(const VoxTri* t) {
  return (long3)(t->n[0], t->n[1], t->n[2]);
}

/* ---- exact rules --------------------------------------------------------------------------------- */

/* The slab-independent part of a triangle's membership test, set up once per triangle (or copy).
 * conservative: the 13-axis separating-axis test of the closed triangle against the closed voxel box
 *   widened by `margin` on every side, [i*S - m, (i+1)*S + m] x ... . The box axes are the loop ranges;
 *   edge x X is constant along a row (row_*); edge x Y, edge x Z and the normal vary linearly with the
 *   column (col_*, 7 of them). An edge's own vertices project to the same value, so the triangle's
 *   projection is [min(0,t), max(0,t)] with t the projection of one vertex relative to v0 (v2 for edge 0,
 *   v1 for edges 1 and 2); the widened box projects to a.(corner - v0) + (S + 2m) [sum of negative a, sum
 *   of positive a].
 * center: the column-centre coverage (top-left rule) and the sign of the plane's depth gradient. */
typedef struct VoxRule {
#if VOXR_MODE == VOXR_MODE_CONSERVATIVE
  long row_ay[3], row_az[3], row_lo[3], row_hi[3];
  long col_ax[7], col_ay[7], col_az[7], col_lo[7], col_hi[7];
  long corner; /* -margin: a box's low corner relative to i*S, j*S, k*S */
#else
  VoxCoverage coverage;
  long sgn;
#endif
} VoxRule;

#if VOXR_MODE == VOXR_MODE_CONSERVATIVE
inline void vox_axis_bounds(long t, long ax, long ay, long az, long size, long* lo, long* hi) {
  *lo = min(0L, t) - size * (max(ax, 0L) + max(ay, 0L) + max(az, 0L));
  *hi = max(0L, t) - size * (min(ax, 0L) + min(ay, 0L) + min(az, 0L));
}
#endif

inline void vox_rule_init(VoxRule* r, const VoxTri* t, const VoxGridParams* grid) {
#if VOXR_MODE == VOXR_MODE_CONSERVATIVE
  const long size = VOX_S + 2 * (long)grid->margin;
  r->corner = -(long)grid->margin;
  const long r1[3] = {t->v[1][0] - t->v[0][0], t->v[1][1] - t->v[0][1], t->v[1][2] - t->v[0][2]};
  const long r2[3] = {t->v[2][0] - t->v[0][0], t->v[2][1] - t->v[0][1], t->v[2][2] - t->v[0][2]};
  for (int e = 0; e < 3; ++e) {
    const int f = e == 2 ? 0 : e + 1;
    const long dx = t->v[f][0] - t->v[e][0], dy = t->v[f][1] - t->v[e][1], dz = t->v[f][2] - t->v[e][2];
    const long* q = e == 0 ? r2 : r1;
    /* edge x X = (0, dz, -dy) */
    r->row_ay[e] = dz;
    r->row_az[e] = -dy;
    vox_axis_bounds(dz * q[1] - dy * q[2], 0, dz, -dy, size, &r->row_lo[e], &r->row_hi[e]);
    /* edge x Y = (-dz, 0, dx) */
    r->col_ax[2 * e] = -dz;
    r->col_ay[2 * e] = 0;
    r->col_az[2 * e] = dx;
    vox_axis_bounds(dx * q[2] - dz * q[0], -dz, 0, dx, size, &r->col_lo[2 * e], &r->col_hi[2 * e]);
    /* edge x Z = (dy, -dx, 0) */
    r->col_ax[2 * e + 1] = dy;
    r->col_ay[2 * e + 1] = -dx;
    r->col_az[2 * e + 1] = 0;
    vox_axis_bounds(dy * q[0] - dx * q[1], dy, -dx, 0, size, &r->col_lo[2 * e + 1], &r->col_hi[2 * e + 1]);
  }
  r->col_ax[6] = t->n[0];
  r->col_ay[6] = t->n[1];
  r->col_az[6] = t->n[2];
  vox_axis_bounds(0, t->n[0], t->n[1], t->n[2], size, &r->col_lo[6], &r->col_hi[6]);
#else
  vox_coverage_init(&r->coverage, t);
  r->sgn = t->n[2] > 0 ? 1 : -1;
#endif
}

/* A writer for one triangle (pass 1 with normals: set w->normal with vox_fixed_normal afterwards;
 * pass 2: `material_id` is the triangle's mesh index). */
inline void vox_writer_init(VoxWriter* w, uint material_id, const VoxGridParams* grid, __global uint* occ,
                            __global const ulong* ranked, __global long* acc, __global uint* material,
                            __global ulong* bricks) {
#if VOX_SPARSE
  w->bricks = bricks;
  w->bdx = (grid->dims[0] + 7u) >> 3;
  w->bdy = (grid->dims[1] + 7u) >> 3;
  w->brick_words = ((ulong)w->bdx * w->bdy * ((grid->dims[2] + 7u) >> 3) + 31u) >> 5;
  w->brick = ~0UL;
  w->slot = ~0UL;
#endif
  w->occ = occ;
  w->ranked = ranked;
  w->acc = acc;
  w->material = material;
  w->word = ~0UL;
  w->mask = 0;
  w->material_id = material_id;
  w->channels = grid->channels;
  w->entries = grid->dims[3];
  w->list_capacity = grid->list_capacity;
  w->normal = (int3)(0);
  w->grid = grid;
  w->color_acc = 0;
  w->texels = 0;
}

/* Pass 1 with colour: the writer's triangle is mesh triangle `index` (vertex indices in tri.xyz), snapped to
 * (x_c, y_c, z_c). */
inline void vox_writer_color(VoxWriter* w, uint4 tri, uint index, long x0, long y0, long z0, long x1, long y1,
                             long z1, long x2, long y2, long z2, VoxColorParams color,
                             __global const uint* vertex_rgba, __global const float* vertex_uv,
                             __global const uint* triangle_look, __global const VoxColorLook* looks,
                             __global const uint* texels, __global long* color_acc) {
  w->color_acc = color_acc;
  w->texels = texels;
  vox_color_geometry(&w->color, x0, y0, z0, x1, y1, z1, x2, y2, z2);
  vox_color_fetch(&w->color, color, tri.x, tri.y, tri.z, index, vertex_rgba, vertex_uv, triangle_look, looks);
}

/* The same from a VoxTri's snapped vertices. */
#define VOX_WRITER_COLOR_TRI(w, tri, index, t)                                                             \
  vox_writer_color(w, tri, index, (t)->v[0][0], (t)->v[0][1], (t)->v[0][2], (t)->v[1][0], (t)->v[1][1],    \
                   (t)->v[1][2], (t)->v[2][0], (t)->v[2][1], (t)->v[2][2], color, vertex_rgba, vertex_uv, \
                   triangle_look, looks, texels, color_acc)

/* Rows [row_first, row_last] of slab k of triangle t through writer w: the work of one copy. With `clip`,
 * large triangles are first clipped to the slab (float) to narrow the rows, and then to each row to narrow
 * the columns; membership is decided by the exact rule either way. */
inline void vox_scan_slab(const VoxTri* t, const VoxRule* rule, const VoxGridParams* grid, int k,
                          int row_first, int row_last, int clip, VoxWriter* w) {
  const int clip_columns = clip && t->last[0] - t->first[0] >= VOX_SMALL_SPAN;
  /* Float error of the clipping, plus the widening of conservative boxes. */
  const float pad = VOX_CLIP_MARGIN + (float)grid->margin / (float)VOXR_SUBVOXEL;
  VoxPoly slab;
  if (clip_columns || (clip && t->last[1] - t->first[1] >= VOX_SMALL_SPAN)) {
    slab.n = 3;
    for (int c = 0; c < 3; ++c)
      for (int a = 0; a < 3; ++a) slab.c[a][c] = (float)t->v[c][a] / (float)VOXR_SUBVOXEL;
    vox_clip_band(&slab, 2, (float)k - pad, (float)(k + 1) + pad);
    if (slab.n == 0) return;
    float lo, hi;
    int first, last;
    vox_poly_range(&slab, 1, &lo, &hi);
    vox_cells(lo, hi, pad, &first, &last);
    row_first = max(row_first, first);
    row_last = min(row_last, last);
  }
  if (row_first > row_last) return;

#if VOXR_MODE == VOXR_MODE_CONSERVATIVE
  const long rel_z = (long)k * VOX_S + rule->corner - t->v[0][2];
  /* The slab is fixed for the whole call: fold its part of every projection in once. */
  long row_z[3], col_z[7];
  for (int e = 0; e < 3; ++e) row_z[e] = rule->row_az[e] * rel_z;
  for (int q = 0; q < 7; ++q) col_z[q] = rule->col_az[q] * rel_z;
#else
  const long rel_z = (long)k * VOX_S - t->v[0][2];
  const long sgn = rule->sgn;
  const long depth_lo = rel_z * t->n[2] * sgn;
  const long depth_hi = (rel_z + VOX_S) * t->n[2] * sgn;
#endif

  for (int j = row_first; j <= row_last; ++j) {
    int col_first = t->first[0], col_last = t->last[0];
    if (clip_columns) {
      VoxPoly row = slab;
#if VOXR_MODE == VOXR_MODE_CONSERVATIVE
      vox_clip_band(&row, 1, (float)j - pad, (float)(j + 1) + pad);
#else
      vox_clip_band(&row, 1, (float)j + 0.5f - pad, (float)j + 0.5f + pad);
#endif
      if (row.n == 0) continue;
      float lo, hi;
      int first, last;
      vox_poly_range(&row, 0, &lo, &hi);
      vox_cells(lo, hi, pad, &first, &last);
      col_first = max(col_first, first);
      col_last = min(col_last, last);
    }
    if (col_first > col_last) continue;
    const ulong row_base = ((ulong)k * grid->dims[1] + (ulong)j) * grid->dims[0];

#if VOXR_MODE == VOXR_MODE_CONSERVATIVE
    const long rel_y = (long)j * VOX_S + rule->corner - t->v[0][1];
    int row_ok = 1;
    for (int e = 0; e < 3; ++e) {
      const long v = rule->row_ay[e] * rel_y + row_z[e];
      row_ok &= rule->row_lo[e] <= v && v <= rule->row_hi[e];
    }
    if (!row_ok) continue;
    const long rel_x = (long)col_first * VOX_S + rule->corner - t->v[0][0];
    long value[7];
    for (int q = 0; q < 7; ++q) value[q] = rule->col_ax[q] * rel_x + rule->col_ay[q] * rel_y + col_z[q];
    for (int i = col_first; i <= col_last; ++i) {
      int inside = 1;
      for (int q = 0; q < 7; ++q) inside &= rule->col_lo[q] <= value[q] && value[q] <= rule->col_hi[q];
      if (inside) vox_emit(w, row_base + (ulong)i, i, j, k);
      for (int q = 0; q < 7; ++q) value[q] += rule->col_ax[q] * VOX_S;
    }
#else
    const long cy = (long)j * VOX_S + VOX_S / 2;
    const long cx0 = (long)col_first * VOX_S + VOX_S / 2;
    long edge[3];
    vox_coverage_start(&rule->coverage, col_first, j, edge);
    long depth = -sgn * (t->n[0] * (cx0 - t->v[0][0]) + t->n[1] * (cy - t->v[0][1]));
    const long depth_step = -sgn * t->n[0] * VOX_S;
    for (int i = col_first; i <= col_last; ++i) {
      const int inside = vox_coverage_next(&rule->coverage, edge) && depth_lo <= depth && depth < depth_hi;
      depth += depth_step;
      if (inside) vox_emit(w, row_base + (ulong)i, i, j, k);
    }
#endif
  }
  vox_flush(w);
}

#endif
