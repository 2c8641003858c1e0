/* vox_direct.cl — small triangles voxelized in one pass, one work item each, with no copy records: the
 * triangle-parallel approach of Schwarz & Seidel (2010, "Fast parallel surface and solid voxelization on
 * GPUs", §3) for the triangles that make up most of a finely tessellated mesh. A work item snaps its
 * triangle and, when the voxel range of its bounding box spans at most VOX_DIRECT_SPAN cells per axis and
 * VOX_DIRECT_CELLS in all, decides every cell with the exact rule of vox_scanline.h — the same predicate
 * as the slice method's copies, so both give the same voxels. Larger triangles are appended to `large` for
 * the papers' expand + scanline path (vox_setup.cl -> scan -> util/expand_copies.cl -> vox_raster.cl).
 *
 * Conservative mode has a dedicated form of the 13-axis test for speed on CPUs: scalar variables only (a
 * private array costs a work-group-sized context array on PoCL), the nine edge axes in 32-bit integers
 * (exact: coordinates are taken relative to the triangle's first cell, so for spans of at most 16 cells and
 * margins of at most 64 units they stay below 2^13, every product below 2^26, an axis value with its steps
 * below 2^29) and the normal axis in 64-bit. Centre mode uses vox_scan_slab.
 * in:  positions (float4), triangles (uint4: indices, material); pass 1 also the ranked occupancy words
 * out: pass 0: occupancy bits, large[] and large_count (the triangles left to the slice path, in any order);
 *      pass 1: the attribute accumulators (and with colour the colour sums, VOX_COLOR_PARAMS) of the small
 *      triangles' voxels; pass 2: their triangle lists
 * shape: one work item per triangle. */
#include "vox_scanline.h"

#ifndef WG_SIZE
#define WG_SIZE 64
#endif
/* Limits of the direct path: cells per axis (the 32-bit bounds above assume at most 16) and in all. A
 * triangle of up to 16 x 16 x 4 cells is cheaper here than as 10-40 copies of the slice path (each copy sets
 * up the 13 axes in 64-bit and clips in float): at 4096^3, where a 1.1 M-triangle mesh's triangles span about
 * 10 cells, this took a fresh run from 4.5 s to 2.3 s on PoCL (bench/results/issue21-sparse-pocl-2core.md). */
#ifndef VOX_DIRECT_SPAN
#define VOX_DIRECT_SPAN 16
#endif
#ifndef VOX_DIRECT_CELLS
#define VOX_DIRECT_CELLS 1024
#endif
#if VOX_DIRECT_SPAN > 16
#error "the direct pass's 32-bit edge axes are proven exact for spans of at most 16 cells"
#endif
/* Widest conservative margin (1/VOXR_SUBVOXEL units) the 32-bit bounds allow. */
#define VOX_DIRECT_MAX_MARGIN 64

#if VOXR_MODE == VOXR_MODE_CONSERVATIVE
/* One edge axis (AX, AY, AZ) of the widened-box SAT as an unsigned range test, (uint)(value - lo) <= width,
 * with the value at cell (di, dj, dk) of the triangle's range = NAME_v + di*NAME_sx + dj*NAME_sy +
 * dk*NAME_sz. T is the projection of the vertex off the edge, relative to v0; r is the first cell's low
 * corner relative to v0. */
#define VOX_EDGE_AXIS(NAME, AX, AY, AZ, T)                                          \
  int NAME##_v, NAME##_sx, NAME##_sy, NAME##_sz;                                    \
  uint NAME##_w;                                                                    \
  {                                                                                 \
    const int ax_ = (AX), ay_ = (AY), az_ = (AZ), t_ = (T);                         \
    const int lo_ = min(0, t_) - size * (max(ax_, 0) + max(ay_, 0) + max(az_, 0));  \
    const int hi_ = max(0, t_) - size * (min(ax_, 0) + min(ay_, 0) + min(az_, 0));  \
    NAME##_v = ax_ * rx + ay_ * ry + az_ * rz - lo_;                                \
    NAME##_w = (uint)(hi_ - lo_);                                                   \
    NAME##_sx = ax_ * VOX_S;                                                        \
    NAME##_sy = ay_ * VOX_S;                                                        \
    NAME##_sz = az_ * VOX_S;                                                        \
  }
#define VOX_ROW_TEST(NAME) ((uint)(NAME##_v + dj * NAME##_sy + dk * NAME##_sz) <= NAME##_w)
#define VOX_CELL_TEST(NAME) ((uint)(NAME##_v + di * NAME##_sx + dj * NAME##_sy + dk * NAME##_sz) <= NAME##_w)

/* Cells [lo, hi] (relative to the unclamped first cell, already clamped to the grid) of a small triangle
 * whose snapped vertices relative to that cell's low corner are u0, u1, u2; `row0` is the linear index of
 * the first cell. */
#define VOX_DIRECT_CONSERVATIVE_BODY                                                                            \
  const int mi = (int)grid.margin;                                                                              \
  const int size = VOX_S + 2 * mi;                                                                              \
  const int rx = -mi - u0x, ry = -mi - u0y, rz = -mi - u0z;                                                     \
  const int e0x = u1x - u0x, e0y = u1y - u0y, e0z = u1z - u0z;                                                  \
  const int e1x = u2x - u1x, e1y = u2y - u1y, e1z = u2z - u1z;                                                  \
  const int e2x = u0x - u2x, e2y = u0y - u2y, e2z = u0z - u2z;                                                  \
  /* v1 - v0 = e0, v2 - v0 = -e2 */                                                                             \
  const int r2x = -e2x, r2y = -e2y, r2z = -e2z;                                                                 \
  /* edge x X = (0, dz, -dy), edge x Y = (-dz, 0, dx), edge x Z = (dy, -dx, 0) */                               \
  VOX_EDGE_AXIS(x0, 0, e0z, -e0y, e0z * r2y - e0y * r2z)                                                        \
  VOX_EDGE_AXIS(x1, 0, e1z, -e1y, e1z * e0y - e1y * e0z)                                                        \
  VOX_EDGE_AXIS(x2, 0, e2z, -e2y, e2z * e0y - e2y * e0z)                                                        \
  VOX_EDGE_AXIS(y0, -e0z, 0, e0x, e0x * r2z - e0z * r2x)                                                        \
  VOX_EDGE_AXIS(y1, -e1z, 0, e1x, e1x * e0z - e1z * e0x)                                                        \
  VOX_EDGE_AXIS(y2, -e2z, 0, e2x, e2x * e0z - e2z * e0x)                                                        \
  VOX_EDGE_AXIS(z0, e0y, -e0x, 0, e0y * r2x - e0x * r2y)                                                        \
  VOX_EDGE_AXIS(z1, e1y, -e1x, 0, e1y * e0x - e1x * e0y)                                                        \
  VOX_EDGE_AXIS(z2, e2y, -e2x, 0, e2y * e0x - e2x * e0y)                                                        \
  /* the normal axis: the plane through v0, in 64-bit */                                                        \
  const long n0 = (long)e0y * r2z - (long)e0z * r2y;                                                            \
  const long n1 = (long)e0z * r2x - (long)e0x * r2z;                                                            \
  const long n2 = (long)e0x * r2y - (long)e0y * r2x;                                                            \
  const long nlo = -(long)size * (max(n0, 0L) + max(n1, 0L) + max(n2, 0L));                                     \
  const ulong nw = (ulong)(-(long)size * (min(n0, 0L) + min(n1, 0L) + min(n2, 0L)) - nlo);                      \
  const long nv = n0 * rx + n1 * ry + n2 * rz - nlo;                                                            \
  const long nsx = n0 * VOX_S, nsy = n1 * VOX_S, nsz = n2 * VOX_S;                                              \
  for (int dk = lz; dk <= hz; ++dk)                                                                             \
    for (int dj = ly; dj <= hy; ++dj) {                                                                         \
      if (!(VOX_ROW_TEST(x0) & VOX_ROW_TEST(x1) & VOX_ROW_TEST(x2))) continue;                                  \
      const ulong row = row0 + ((ulong)dk * grid.dims[1] + (ulong)dj) * grid.dims[0];                            \
      long nval = nv + lx * nsx + dj * nsy + dk * nsz;                                                          \
      for (int di = lx; di <= hx; ++di, nval += nsx) {                                                          \
        const int inside = ((ulong)nval <= nw) & VOX_CELL_TEST(y0) & VOX_CELL_TEST(y1) & VOX_CELL_TEST(y2) &    \
                           VOX_CELL_TEST(z0) & VOX_CELL_TEST(z1) & VOX_CELL_TEST(z2);                           \
        if (inside) vox_emit(&w, row + (ulong)di, fx + di, fy + dj, fz + dk);                                   \
      }                                                                                                         \
    }
#endif

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void vox_direct(
    VoxGridParams grid, __global const float4* positions, __global const uint4* triangles,
    __global uint* large, __global uint* large_count, __global uint* occ, __global const ulong* ranked,
    __global long* acc, __global uint* material, __global ulong* bricks, VOX_COLOR_PARAMS) {
  const uint index = get_global_id(0);
  if (index >= grid.triangle_count) return;
  const uint4 tri = triangles[index];
  /* Snapped vertices as scalars (vox_snap_triangle's arithmetic without its private arrays, which PoCL
   * would turn into work-group-sized context arrays). */
  const float4 p0 = positions[tri.x], p1 = positions[tri.y], p2 = positions[tri.z];
  const float* g = grid.world_to_grid;
#define VOX_SNAP(p, a) vox_snap(((g[4 * a] * p.x + g[4 * a + 1] * p.y) + g[4 * a + 2] * p.z) + g[4 * a + 3])
  /* z relative to a window's first slice (VoxGridParams.first_slice), as vox_snap_triangle does */
  const long zs = (long)grid.first_slice * VOXR_SUBVOXEL;
  const long x0 = VOX_SNAP(p0, 0), y0 = VOX_SNAP(p0, 1), z0 = VOX_SNAP(p0, 2) - zs;
  const long x1 = VOX_SNAP(p1, 0), y1 = VOX_SNAP(p1, 1), z1 = VOX_SNAP(p1, 2) - zs;
  const long x2 = VOX_SNAP(p2, 0), y2 = VOX_SNAP(p2, 1), z2 = VOX_SNAP(p2, 2) - zs;
#undef VOX_SNAP
  const long lo_x = min(x0, min(x1, x2)), lo_y = min(y0, min(y1, y2)), lo_z = min(z0, min(z1, z2));
  const long hi_x = max(x0, max(x1, x2)), hi_y = max(y0, max(y1, y2)), hi_z = max(z0, max(z1, z2));
  /* The cells under the raster rule (vox_derive), unclamped. */
#if VOXR_MODE == VOXR_MODE_CONSERVATIVE
  const long m = (long)grid.margin;
  const int fx = (int)vox_floor_cell(lo_x - m - 1), fy = (int)vox_floor_cell(lo_y - m - 1);
  const int fz = (int)vox_floor_cell(lo_z - m - 1);
  const int tx = (int)vox_floor_cell(hi_x + m), ty = (int)vox_floor_cell(hi_y + m), tz = (int)vox_floor_cell(hi_z + m);
#else
  const int fx = (int)vox_floor_cell(lo_x - VOX_S / 2 + VOX_S - 1), fy = (int)vox_floor_cell(lo_y - VOX_S / 2 + VOX_S - 1);
  const int fz = (int)vox_floor_cell(lo_z);
  const int tx = (int)vox_floor_cell(hi_x - VOX_S / 2), ty = (int)vox_floor_cell(hi_y - VOX_S / 2);
  const int tz = (int)vox_floor_cell(hi_z);
#endif
  /* ... and the part inside the grid, relative to the first cell. */
  const int lx = max(fx, 0) - fx, ly = max(fy, 0) - fy, lz = max(fz, 0) - fz;
  const int hx = min(tx, (int)grid.dims[0] - 1) - fx, hy = min(ty, (int)grid.dims[1] - 1) - fy;
  const int hz = min(tz, (int)grid.dims[2] - 1) - fz;
  if (lx > hx || ly > hy || lz > hz) return; /* misses the grid */
  const int sx = tx - fx + 1, sy = ty - fy + 1, sz = tz - fz + 1;
  int small = sx <= VOX_DIRECT_SPAN && sy <= VOX_DIRECT_SPAN && sz <= VOX_DIRECT_SPAN &&
              sx * sy * sz <= VOX_DIRECT_CELLS;
#if VOXR_MODE == VOXR_MODE_CONSERVATIVE
  small = small && grid.margin <= VOX_DIRECT_MAX_MARGIN;
#endif
  if (!small) {
#if VOX_PASS == 0
    large[atomic_inc(large_count)] = index;
#endif
    return;
  }

  VoxWriter w;
  vox_writer_init(&w, VOX_PASS == 2 ? index : tri.w, &grid, occ, ranked, acc, material, bricks);
#if VOX_PASS == 1
  if (grid.channels & VOX_CH_COLOR)
    vox_writer_color(&w, tri, index, x0, y0, z0, x1, y1, z1, x2, y2, z2, color, vertex_rgba, vertex_uv,
                     triangle_look, looks, texels, color_acc);
#endif
#if VOXR_MODE == VOXR_MODE_CONSERVATIVE
#if VOX_PASS == 1
  if (grid.channels & VOX_CH_NORMAL)
    vox_fixed_normal(vox_cross((long3)(x1 - x0, y1 - y0, z1 - z0), (long3)(x2 - x0, y2 - y0, z2 - z0)), &w.normal);
#endif
  const long bx = (long)fx * VOX_S, by = (long)fy * VOX_S, bz = (long)fz * VOX_S;
  const int u0x = (int)(x0 - bx), u0y = (int)(y0 - by), u0z = (int)(z0 - bz);
  const int u1x = (int)(x1 - bx), u1y = (int)(y1 - by), u1z = (int)(z1 - bz);
  const int u2x = (int)(x2 - bx), u2y = (int)(y2 - by), u2z = (int)(z2 - bz);
  /* fx may be negative (cells below the grid are skipped by the loop ranges) */
  const ulong row0 = (ulong)(((long)fz * grid.dims[1] + fy) * (long)grid.dims[0] + fx);
  if ((sx == 1) + (sy == 1) + (sz == 1) >= 2) {
    /* A triangle within one cell along two axes meets every cell of its range: its extent along those axes
     * lies inside the cell's widened box, and it has a point at every coordinate of its range along the
     * third. No test is needed (the most common case on fine meshes at coarse resolutions). */
    for (int dk = lz; dk <= hz; ++dk)
      for (int dj = ly; dj <= hy; ++dj) {
        const ulong row = row0 + ((ulong)dk * grid.dims[1] + (ulong)dj) * grid.dims[0];
        for (int di = lx; di <= hx; ++di) vox_emit(&w, row + (ulong)di, fx + di, fy + dj, fz + dk);
      }
  } else {
    VOX_DIRECT_CONSERVATIVE_BODY
  }
  vox_flush(&w);
#else
  VoxTri t;
  t.v[0][0] = x0, t.v[0][1] = y0, t.v[0][2] = z0;
  t.v[1][0] = x1, t.v[1][1] = y1, t.v[1][2] = z1;
  t.v[2][0] = x2, t.v[2][1] = y2, t.v[2][2] = z2;
  vox_derive(&t, &grid);
  if (t.n[2] == 0) return; /* edge-on: covers no column centre */
#if VOX_PASS == 1
  if (grid.channels & VOX_CH_NORMAL) vox_fixed_normal(vox_tri_normal(&t), &w.normal);
#endif
  VoxRule rule;
  vox_rule_init(&rule, &t, &grid);
  for (int k = t.first[2]; k <= t.last[2]; ++k) vox_scan_slab(&t, &rule, &grid, k, t.first[1], t.last[1], 0, &w);
#endif
}
