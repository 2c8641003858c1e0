/* grid_view.h — how a kernel reads a voxel grid that stays on the device (host/grid/device_voxel_grid.h):
 * occupancy and inside as dense bits, the sparse channels (count, normal, material) through the rank index,
 * and voxel-by-voxel ray traversal. A kernel declares VOXR_GRID_VIEW_PARAMS among its parameters (the host
 * passes DeviceVoxelGrid::view_args() there) and builds its view with VOXR_GRID_VIEW():
 *
 *   __kernel void shade(VOXR_GRID_VIEW_PARAMS, __global float* out) {
 *     const GridView g = VOXR_GRID_VIEW();
 *     const ulong v = gv_linear(&g, i, j, k);
 *     if (gv_occupied(&g, v)) { const uint r = gv_rank(&g, v); float3 n = gv_normal(&g, r); ... }
 *   }
 *
 * Coordinates: voxel (i, j, k) is the box [i, i+1] x [j, j+1] x [k, k+1] in grid units; linear index
 * (k * dims_y + j) * dims_x + i, 64-bit. Channel accessors of a channel the grid lacks return 0. */
#ifndef GRID_VIEW_H
#define GRID_VIEW_H

#include "voxr_layout.h"

#ifndef VOX_CH_OCC
#error "grid_view.h needs the channel defines of host/grid/channel_table.h (channel_defines)"
#endif

/* The buffer parameters are named gv_buf_*: named like the accessors (gv_count, gv_normal, ...) they would
 * hide those functions inside the kernel that declares them. */
#define VOXR_GRID_VIEW_PARAMS                                                                  \
  VoxGridView gv_params, __global const uint *gv_buf_occ, __global const ulong *gv_buf_ranked, \
      __global const uint *gv_buf_count, __global const float *gv_buf_normal,                  \
      __global const uint *gv_buf_material, __global const uint *gv_buf_inside
#define VOXR_GRID_VIEW() \
  gv_make(&gv_params, gv_buf_occ, gv_buf_ranked, gv_buf_count, gv_buf_normal, gv_buf_material, gv_buf_inside)
/* A second grid in the same kernel (e.g. voxel refraction's coarse level): its parameters named n_params,
 * n_occ, ... and its view. */
#define VOXR_GRID_VIEW_PARAMS_NAMED(n)                                                                     \
  VoxGridView n##_params, __global const uint *n##_occ, __global const ulong *n##_ranked,                  \
      __global const uint *n##_count, __global const float *n##_normal, __global const uint *n##_material, \
      __global const uint *n##_inside
#define VOXR_GRID_VIEW_NAMED(n) \
  gv_make(&n##_params, n##_occ, n##_ranked, n##_count, n##_normal, n##_material, n##_inside)

typedef struct GridView {
  __global const uint* occ;
  __global const ulong* ranked; /* the rank index (voxr_layout.h VOXR_RANKED) */
  __global const uint* count;
  __global const float* normal; /* 3 floats per set voxel */
  __global const uint* material;
  __global const uint* inside;
  uint dims_x, dims_y, dims_z;
  uint channels;
  uint has_rank_index;
  uint voxels_set; /* entries of the sparse channels: a rank past them reads as absent (a frame whose
                      set-voxel count outgrew the capacity the host allocated is rendered again) */
} GridView;

inline GridView gv_make(const VoxGridView* p, __global const uint* occ, __global const ulong* ranked,
                        __global const uint* count, __global const float* normal,
                        __global const uint* material, __global const uint* inside) {
  GridView g;
  g.occ = occ;
  g.ranked = ranked;
  g.count = count;
  g.normal = normal;
  g.material = material;
  g.inside = inside;
  g.dims_x = p->dims[0];
  g.dims_y = p->dims[1];
  g.dims_z = p->dims[2];
  g.channels = p->channels;
  g.has_rank_index = p->has_rank_index;
  g.voxels_set = p->voxels_set;
  return g;
}

inline int gv_has(const GridView* g, uint channel) {
  return (g->channels & channel) != 0;
}

inline int gv_contains(const GridView* g, int i, int j, int k) {
  return i >= 0 && j >= 0 && k >= 0 && (uint)i < g->dims_x && (uint)j < g->dims_y && (uint)k < g->dims_z;
}

inline ulong gv_linear(const GridView* g, int i, int j, int k) {
  return ((ulong)k * g->dims_y + (ulong)j) * g->dims_x + (ulong)i;
}

inline int gv_occupied(const GridView* g, ulong linear) {
  return (g->occ[linear >> 5] >> (uint)(linear & 31)) & 1u;
}

inline int gv_inside(const GridView* g, ulong linear) {
  return gv_has(g, VOX_CH_INSIDE) ? (int)((g->inside[linear >> 5] >> (uint)(linear & 31)) & 1u) : 0;
}

/* Whether gv_rank may be called: the host builds the rank index whenever a sparse channel exists, or on
 * request (build_rank_index). */
inline int gv_has_rank(const GridView* g) {
  return g->has_rank_index != 0;
}

/* The rank of an occupied voxel among the set voxels: its index into the sparse channels (gv_has_rank must
 * hold). */
inline uint gv_rank(const GridView* g, ulong linear) {
  const ulong w = g->ranked[linear >> 5];
  return VOXR_RANKED_RANK(w) + popcount(VOXR_RANKED_BITS(w) & ((1u << (uint)(linear & 31)) - 1u));
}

inline uint gv_count(const GridView* g, uint rank) {
  return gv_has(g, VOX_CH_COUNT) && rank < g->voxels_set ? g->count[rank] : 0u;
}

inline float3 gv_normal(const GridView* g, uint rank) {
  return gv_has(g, VOX_CH_NORMAL) && rank < g->voxels_set ? vload3(rank, g->normal) : (float3)(0.0f);
}

inline uint gv_material(const GridView* g, uint rank) {
  return gv_has(g, VOX_CH_MATERIAL) && rank < g->voxels_set ? g->material[rank] : 0u;
}

/* World point -> grid units, with the grid's affine (VoxGridView.world_to_grid). */
inline float3 gv_to_grid(const VoxGridView* p, float3 w) {
  const float* m = p->world_to_grid;
  return (float3)(((m[0] * w.x + m[1] * w.y) + m[2] * w.z) + m[3],
                  ((m[4] * w.x + m[5] * w.y) + m[6] * w.z) + m[7],
                  ((m[8] * w.x + m[9] * w.y) + m[10] * w.z) + m[11]);
}

/* ---- voxel traversal: the 3-D DDA of Amanatides & Woo (1987), in grid units --------------------------- */

typedef struct GvRay {
  int i, j, k;         /* current voxel */
  int si, sj, sk;      /* step along each axis: -1, 0 or +1 */
  float tx, ty, tz;    /* ray parameter of the next boundary crossing along each axis */
  float dtx, dty, dtz; /* parameter per voxel along each axis */
  float t;             /* parameter where the current voxel was entered */
  float t_exit;        /* parameter where the ray leaves the grid */
} GvRay;

/* [*t0, *t1]: where o + t d lies in the slab [0, hi] of one axis (inv = 1 / d). A ray parallel to the axis
 * (d = +-0) lies in it for every t when 0 <= o < hi (cells are half-open, as floor() assigns voxels) and
 * never otherwise. The products with inv = +-inf cannot say so: an origin on a face gives 0 * inf = NaN and
 * fmin(NaN, inf) = inf, so a ray lying in the grid's x = 0 face missed the grid, and a zero direction from
 * outside met it at t = inf. */
inline void gv_slab(float o, float d, float inv, float hi, float* t0, float* t1) {
  if (d == 0.0f) {
    const int in = o >= 0.0f && o < hi;
    *t0 = in ? -INFINITY : INFINITY;
    *t1 = in ? INFINITY : -INFINITY;
    return;
  }
  const float a = (0.0f - o) * inv, b = (hi - o) * inv;
  *t0 = fmin(a, b);
  *t1 = fmax(a, b);
}

/* The stepping state of a ray from `origin` along `dir` (inv = 1 / dir) out of the current voxel (r->i, j,
 * k): step signs, parameter per voxel and of the next boundary crossing along each axis. */
inline void gv_ray_steps(GvRay* r, float3 origin, float3 dir, float3 inv) {
  r->si = dir.x > 0.0f ? 1 : dir.x < 0.0f ? -1 : 0;
  r->sj = dir.y > 0.0f ? 1 : dir.y < 0.0f ? -1 : 0;
  r->sk = dir.z > 0.0f ? 1 : dir.z < 0.0f ? -1 : 0;
  r->dtx = r->si != 0 ? fabs(inv.x) : INFINITY;
  r->dty = r->sj != 0 ? fabs(inv.y) : INFINITY;
  r->dtz = r->sk != 0 ? fabs(inv.z) : INFINITY;
  r->tx = r->si != 0 ? ((float)(r->i + (r->si > 0)) - origin.x) * inv.x : INFINITY;
  r->ty = r->sj != 0 ? ((float)(r->j + (r->sj > 0)) - origin.y) * inv.y : INFINITY;
  r->tz = r->sk != 0 ? ((float)(r->k + (r->sk > 0)) - origin.z) * inv.z : INFINITY;
}

/* Starts the traversal of origin + t dir, t >= 0 (grid units), at the first voxel of the grid the ray
 * meets. Returns 0 when it misses the grid. */
inline int gv_ray_begin(GvRay* r, const GridView* g, float3 origin, float3 dir) {
  const float3 inv = (float3)(1.0f) / dir; /* +-inf on axes the ray is parallel to */
  float t0x, t1x, t0y, t1y, t0z, t1z;
  gv_slab(origin.x, dir.x, inv.x, (float)g->dims_x, &t0x, &t1x);
  gv_slab(origin.y, dir.y, inv.y, (float)g->dims_y, &t0y, &t1y);
  gv_slab(origin.z, dir.z, inv.z, (float)g->dims_z, &t0z, &t1z);
  const float t_enter = fmax(fmax(fmax(t0x, t0y), t0z), 0.0f);
  const float t_exit = fmin(fmin(t1x, t1y), t1z);
  if (!(t_enter <= t_exit)) return 0;
  const float3 p = origin + t_enter * dir;
  r->i = clamp((int)floor(p.x), 0, (int)g->dims_x - 1);
  r->j = clamp((int)floor(p.y), 0, (int)g->dims_y - 1);
  r->k = clamp((int)floor(p.z), 0, (int)g->dims_z - 1);
  gv_ray_steps(r, origin, dir, inv);
  r->t = t_enter;
  r->t_exit = t_exit;
  return 1;
}

/* Moves to the next voxel along the ray. Returns the axis crossed (0, 1, 2), or -1 when the ray leaves the
 * grid (the current voxel is then unchanged). Ties cross x before y before z. */
inline int gv_ray_step(GvRay* r, const GridView* g) {
  int axis;
  if (r->tx <= r->ty && r->tx <= r->tz)
    axis = 0;
  else if (r->ty <= r->tz)
    axis = 1;
  else
    axis = 2;
  if (axis == 0) {
    if (r->si == 0 || (uint)(r->i + r->si) >= g->dims_x) return -1;
    r->i += r->si;
    r->t = r->tx;
    r->tx += r->dtx;
  } else if (axis == 1) {
    if (r->sj == 0 || (uint)(r->j + r->sj) >= g->dims_y) return -1;
    r->j += r->sj;
    r->t = r->ty;
    r->ty += r->dty;
  } else {
    if (r->sk == 0 || (uint)(r->k + r->sk) >= g->dims_z) return -1;
    r->k += r->sk;
    r->t = r->tz;
    r->tz += r->dtz;
  }
  return axis;
}

#endif
