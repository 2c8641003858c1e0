/* raster_coverage.h — which pixel centres of one tile a binned primitive (voxr_layout.h RasterPrim, written
 * by raster_setup.cl) covers, and its depth there. Every kernel that consumes the rasterizer's records
 * includes this and adds its own per-pixel action:
 *
 *   const CopyRecord rec = records[gid];
 *   __global const RasterPrim* prim = prims + rec.triangle;
 *   ulong mask = raster_tile_mask(prim, rec.cell, width, height);
 *   uint x, y;
 *   while (raster_next_pixel(&mask, rec.cell, &x, &y)) { ... raster_depth_at(prim, x, y, width, height) ... }
 *
 * Coverage is exact: the pixel centre (x + 1/2, y + 1/2) against the polygon's edge functions in 64-bit
 * integers (snapped vertices, 1/VOXR_SUBPIXEL pixel), with the top-left rule for centres exactly on an edge
 * (inside for left edges and for horizontal top edges), so two triangles sharing an edge never both cover,
 * nor both miss, a centre on it. Mirrored on the host by host/render/reference_raster.cpp. */
#ifndef RASTER_COVERAGE_H
#define RASTER_COVERAGE_H

#include "voxr_layout.h"

#pragma OPENCL FP_CONTRACT OFF

#define RASTER_S ((long)VOXR_SUBPIXEL)
#define RASTER_TILE VOXR_RASTER_TILE

/* floor(a / VOXR_SUBPIXEL) with shifts of non-negative values only. */
inline long raster_floor_pixel(long a) {
  return a >= 0 ? a >> VOXR_SUBPIXEL_BITS : ~((~a) >> VOXR_SUBPIXEL_BITS);
}

/* Edge functions E_i(P) = dx_i (P.y - y_i) - dy_i (P.x - x_i) of edge i (vertex i to i+1) minus its tie bias,
 * stepped per column and per row over the pixels of the tile at (x0, y0) (cols x rows of them in the image)
 * whose centres lie in the polygon's bounding box. The polygon is positively oriented (rows down), so a
 * centre is covered when every biased E_i >= 0. N edges are evaluated; edges at or beyond vertex_count
 * always pass. |coordinates| < 2^29 and |centres| < 2^22, so every product is < 2^61. */
#define RASTER_MASK_BODY(N)                                                                             \
  long lo_x = prim->x[0], hi_x = lo_x, lo_y = prim->y[0], hi_y = lo_y;                                  \
  for (int i = 1; i < N; ++i) {                                                                         \
    if (i < n) {                                                                                        \
      lo_x = min(lo_x, (long)prim->x[i]);                                                               \
      hi_x = max(hi_x, (long)prim->x[i]);                                                               \
      lo_y = min(lo_y, (long)prim->y[i]);                                                               \
      hi_y = max(hi_y, (long)prim->y[i]);                                                               \
    }                                                                                                   \
  }                                                                                                     \
  /* Columns and rows of the tile whose centres (x + 1/2) S lie in [lo, hi]. */                         \
  const int c_first = (int)max(raster_floor_pixel(lo_x - RASTER_S / 2 + RASTER_S - 1) - x0, 0L);        \
  const int c_last = (int)min(raster_floor_pixel(hi_x - RASTER_S / 2) - x0, (long)cols - 1);            \
  const int r_first = (int)max(raster_floor_pixel(lo_y - RASTER_S / 2 + RASTER_S - 1) - y0, 0L);        \
  const int r_last = (int)min(raster_floor_pixel(hi_y - RASTER_S / 2) - y0, (long)rows - 1);            \
  ulong mask = 0;                                                                                       \
  if (c_first > c_last || r_first > r_last) return mask;                                                \
  long e[N], step_x[N], step_y[N];                                                                      \
  const long cx = (long)(x0 + c_first) * RASTER_S + RASTER_S / 2;                                       \
  const long cy = (long)(y0 + r_first) * RASTER_S + RASTER_S / 2;                                       \
  for (int i = 0; i < N; ++i) {                                                                         \
    if (i < n) {                                                                                        \
      const int j = i + 1 < n ? i + 1 : 0;                                                              \
      const long xi = prim->x[i], yi = prim->y[i];                                                      \
      const long dx = (long)prim->x[j] - xi, dy = (long)prim->y[j] - yi;                                \
      /* Top-left rule: left edges run up the image (dy < 0), top edges run right (dy == 0, dx > 0). */ \
      const long bias = (dy < 0 || (dy == 0 && dx > 0)) ? 0 : 1;                                        \
      e[i] = dx * (cy - yi) - dy * (cx - xi) - bias;                                                    \
      step_x[i] = -dy * RASTER_S;                                                                       \
      step_y[i] = dx * RASTER_S;                                                                        \
    } else {                                                                                            \
      e[i] = 0;                                                                                         \
      step_x[i] = 0;                                                                                    \
      step_y[i] = 0;                                                                                    \
    }                                                                                                   \
  }                                                                                                     \
  for (int r = r_first; r <= r_last; ++r) {                                                             \
    long f[N];                                                                                          \
    for (int i = 0; i < N; ++i) f[i] = e[i];                                                            \
    for (int c = c_first; c <= c_last; ++c) {                                                           \
      int inside = 1;                                                                                   \
      for (int i = 0; i < N; ++i) {                                                                     \
        inside &= f[i] >= 0;                                                                            \
        f[i] += step_x[i];                                                                              \
      }                                                                                                 \
      if (inside) mask |= 1ul << (r * RASTER_TILE + c);                                                 \
    }                                                                                                   \
    for (int i = 0; i < N; ++i) e[i] += step_y[i];                                                      \
  }                                                                                                     \
  return mask;

/* Triangles (the common case) with three edges in registers; clipped polygons with all eight. */
inline ulong raster_mask_3(__global const RasterPrim* prim, int n, int x0, int y0, uint cols, uint rows) {
  RASTER_MASK_BODY(3)
}
inline ulong raster_mask_8(__global const RasterPrim* prim, int n, int x0, int y0, uint cols, uint rows) {
  RASTER_MASK_BODY(VOXR_RASTER_MAX_VERTICES)
}

/* Covered pixels of tile `tile` (column in the low 16 bits, row in the high 16): bit r * RASTER_TILE + c for
 * pixel (tile column * RASTER_TILE + c, tile row * RASTER_TILE + r); pixels outside the image are never set.
 */
inline ulong raster_tile_mask(__global const RasterPrim* prim, uint tile, uint width, uint height) {
  const int n = (int)prim->vertex_count;
  if (n < 3 || n > VOXR_RASTER_MAX_VERTICES) return 0;
  const uint x0 = (tile & 0xffffu) * RASTER_TILE, y0 = (tile >> 16) * RASTER_TILE;
  if (x0 >= width || y0 >= height) return 0;
  const uint cols = min((uint)RASTER_TILE, width - x0), rows = min((uint)RASTER_TILE, height - y0);
  return n == 3 ? raster_mask_3(prim, n, (int)x0, (int)y0, cols, rows)
                : raster_mask_8(prim, n, (int)x0, (int)y0, cols, rows);
}

/* Takes the lowest set pixel out of `mask`: its image position in (x, y). Returns 0 when none is left. */
inline int raster_next_pixel(ulong* mask, uint tile, uint* x, uint* y) {
  if (*mask == 0) return 0;
  const ulong lowest = *mask & (~*mask + 1ul);
  const uint bit = 63u - (uint)clz(lowest);
  *mask ^= lowest;
  *x = (tile & 0xffffu) * RASTER_TILE + bit % RASTER_TILE;
  *y = (tile >> 16) * RASTER_TILE + bit / RASTER_TILE;
  return 1;
}

/* z_ndc of the primitive's plane at the centre of pixel (x, y), clamped to [0, 1] (never -0 or NaN). The
 * evaluation order is fixed (no contraction), so the host reproduces it bit for bit. */
inline float raster_depth_at(__global const RasterPrim* prim, uint x, uint y, uint width, uint height) {
  const float dx = ((float)x + 0.5f) - (float)width * 0.5f;
  const float dy = ((float)y + 0.5f) - (float)height * 0.5f;
  const float z = (prim->depth[0] * dx + prim->depth[1] * dy) + prim->depth[2];
  const float above = z > 0.0f ? z : 0.0f;
  return above < 1.0f ? above : 1.0f;
}

/* The visibility word of a fragment: depth bits high, triangle low. */
inline ulong raster_visibility_word(float depth, uint triangle) {
  return ((ulong)as_uint(depth) << 32) | (ulong)triangle;
}

#endif
