/* slicemap_raster.cl — slicemap stage 3: rasterize one tile of a triangle's projection once, in 2D. Each
 * column centre ((i + 1/2) S, (j + 1/2) S) the triangle covers (top-left tie rule, exact 64-bit integers as
 * in vox_scanline.h's centre mode) is one fragment with the exact fixed-point depth zf = floor(S * z) of the
 * triangle's plane there; fragments with zf outside [0, Z) (Z = dims.z * S) are dropped.
 *   SLICEMAP_PASS 0 (depth pre-pass, local slicing): per column atomic_max of (Z - zf) and of (zf + 1), so a
 *                   zero-filled buffer means "no fragment" and the column's near/far are exact integers.
 *   SLICEMAP_PASS 1 (bits): atomic_or of the fragment's bit into the column's slicemap. SLICEMAP_LOCAL 0:
 *                   bit = zf / S (uniform slicing); 1: bit = (zf - near) * B / (far - near + 1), B = dims.z.
 * in:  snapped triangles (slicemap_setup.cl), records (triangle, tile row << 16 | tile column), depth_range
 *      (pass 1 with SLICEMAP_LOCAL: the depth pass's output)
 * out: depth_range[2c] = Z - near, depth_range[2c+1] = far + 1 (pass 0), or slicemap[c * W + bit / 32] (pass
 *      1), c = j * dims.x + i, W = ceil(dims.z / 32).
 * shape: one work item per record: at most SLICEMAP_TILE_ROWS x SLICEMAP_TILE_COLS column centres. */
#include "voxr_layout.h"

#define VOXR_MODE VOXR_MODE_CENTER
#include "vox_triangle.h"

#ifndef WG_SIZE
#define WG_SIZE 256
#endif
#ifndef SLICEMAP_TILE_ROWS
#define SLICEMAP_TILE_ROWS 8
#endif
#ifndef SLICEMAP_TILE_COLS
#define SLICEMAP_TILE_COLS 8
#endif
#ifndef SLICEMAP_PASS
#define SLICEMAP_PASS 1
#endif
#ifndef SLICEMAP_LOCAL
#define SLICEMAP_LOCAL 0
#endif

/* floor(a / d) for d > 0. */
inline long slicemap_floor_div(long a, long d) {
  long q = a / d;
  if (q * d > a) --q;
  return q;
}

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void slicemap_raster(
    VoxGridParams grid, __global const VoxSnappedTriangle* snapped, __global const CopyRecord* records, uint record_count,
    __global uint* depth_range, __global uint* slicemap) {
  const uint gid = get_global_id(0);
  if (gid >= record_count) return;
  const CopyRecord rec = records[gid];
  VoxTri t;
  vox_fetch_triangle(&t, snapped, rec.triangle);
  vox_derive(&t, &grid);

  const int row_first = t.first[1] + (int)VOXR_CELL_ROW(rec.cell) * SLICEMAP_TILE_ROWS;
  const int row_last = min(t.last[1], row_first + SLICEMAP_TILE_ROWS - 1);
  const int col_first = t.first[0] + (int)VOXR_CELL_COLUMN(rec.cell) * SLICEMAP_TILE_COLS;
  const int col_last = min(t.last[0], col_first + SLICEMAP_TILE_COLS - 1);

  VoxCoverage coverage; /* the centre rule, shared with vox_scanline.h */
  vox_coverage_init(&coverage, &t);

  /* Plane depth at a centre: z S = v0z + num / d with num = -sgn (n.x (cx - v0x) + n.y (cy - v0y)) and
   * d = |n.z| > 0. zf = v0z + floor(num / d), kept as quotient q and remainder r in [0, d), stepped along
   * the row. */
  const long sgn = t.n[2] > 0 ? 1 : -1;
  const long d = sgn * t.n[2];
  const long step = -sgn * t.n[0] * VOX_S;
  const long step_q = slicemap_floor_div(step, d);
  const long step_r = step - step_q * d;

  const uint dims_x = grid.dims[0], dims_y = grid.dims[1], slices = grid.dims[2];
  const long z_end = (long)slices * VOX_S;
  const ulong words_per_column = (slices + 31) / 32;

  for (int j = row_first; j <= row_last; ++j) {
    const long cy = (long)j * VOX_S + VOX_S / 2;
    const long cx0 = (long)col_first * VOX_S + VOX_S / 2;
    long edge[3];
    vox_coverage_start(&coverage, col_first, j, edge);
    const long num = -sgn * (t.n[0] * (cx0 - t.v[0][0]) + t.n[1] * (cy - t.v[0][1]));
    long q = slicemap_floor_div(num, d);
    long r = num - q * d;
    for (int i = col_first; i <= col_last; ++i) {
      const int inside = vox_coverage_next(&coverage, edge);
      const long zf = t.v[0][2] + q;
      q += step_q;
      r += step_r;
      if (r >= d) {
        r -= d;
        ++q;
      }
      if (!inside || zf < 0 || zf >= z_end || (uint)i >= dims_x || (uint)j >= dims_y) continue;
      const ulong column = (ulong)j * dims_x + (ulong)i;
#if SLICEMAP_PASS == 0
      /* Plain reads skip most locked writes; values only grow during this pass, so the race is benign. */
      const uint near_code = (uint)(z_end - zf), far_code = (uint)(zf + 1);
      if (depth_range[2 * column] < near_code) atomic_max(depth_range + 2 * column, near_code);
      if (depth_range[2 * column + 1] < far_code) atomic_max(depth_range + 2 * column + 1, far_code);
#else
#if SLICEMAP_LOCAL
      const long near = z_end - (long)depth_range[2 * column];
      const long far = (long)depth_range[2 * column + 1] - 1;
      /* The depth pass saw this fragment, so near <= zf <= far and the bit is in [0, slices). */
      if (zf < near || zf > far) continue;
      const ulong bit = (ulong)(zf - near) * slices / (ulong)(far - near + 1);
#else
      const ulong bit = (ulong)zf >> VOXR_SUBVOXEL_BITS;
#endif
      if (bit < slices) atomic_or(slicemap + column * words_per_column + (bit >> 5), 1u << (uint)(bit & 31));
#endif
    }
  }
}
