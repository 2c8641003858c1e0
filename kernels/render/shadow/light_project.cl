/* light_project.cl — the light's grid fitted and the light mesh built on the device, so a frame makes no
 * host pass over triangles. CPU references, mirrored float operation for float operation (no contraction):
 * host/render/light_frame.cpp fit_light_frame and project_to_light_grid, host/voxelize/triangle_splitter.cpp
 * split_oversized_triangles with SplitCull::kGrid.
 *   light_reduce_init  one work item: the reduction slots to their empty values
 *   light_fit_casters  one work item per scene triangle: the light-space box of each triangle that can
 *                      shadow a receiver (kept per triangle) -> the casters' footprint (work-group tree
 *                      reduction, then ordered-uint atomic min/max)
 *   light_fit_near     one work item per scene triangle: the nearest depth of the kept casters whose box
 *                      overlaps the footprint (the receivers' columns cut to the casters')
 *   light_vertices     one work item per scene vertex (point light): into the light's view and grid units
 *   light_pieces       one work item per scene triangle: (point light) near-clip and map into grid units and
 *                      cull; then pieces of triangles longer than LIGHT_SPLIT_EXTENT voxels. Pass 0 counts
 *                      pieces per triangle, the survivors' bounds, split triangles and overflow; pass 1
 *                      writes the pieces (non-indexed: 3 float4 corners each) at the scanned offsets.
 * Reduction slots (uint, LIGHT_SLOTS; floats as order-preserving keys): LIGHT_CAST + 0..3 the casters'
 * footprint lo.x, lo.y, hi.x, hi.y; LIGHT_NEAR their nearest depth; LIGHT_BOUNDS + 0..5 the light mesh's
 * bounds lo xyz, hi xyz; LIGHT_SPLIT triangles split; LIGHT_OVERFLOW pieces past LIGHT_SPLIT_DEPTH. */
#pragma OPENCL FP_CONTRACT OFF

#include "voxr_layout.h"

#ifndef WG_SIZE
#define WG_SIZE 256
#endif
#ifndef LIGHT_SPLIT_EXTENT
#define LIGHT_SPLIT_EXTENT 2000.0f
#endif
#ifndef LIGHT_SPLIT_DEPTH
#define LIGHT_SPLIT_DEPTH 16
#endif
#ifndef LIGHT_CAST
#define LIGHT_CAST 0
#define LIGHT_NEAR 4
#define LIGHT_BOUNDS 5
#define LIGHT_SPLIT 11
#define LIGHT_OVERFLOW 12
#define LIGHT_SLOTS 13
#endif

/* Order-preserving float -> uint (finite values and infinities). */
inline uint lf_key(float x) {
  const uint u = as_uint(x);
  return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}
inline float lf_value(uint k) {
  return as_float((k & 0x80000000u) ? (k & 0x7fffffffu) : ~k);
}

/* glm's operations in its order: min/max as (b < a ? b : a), dot as (x + y) + z, mat3 rows x vector. */
inline float lf_min(float a, float b) {
  return b < a ? b : a;
}
inline float lf_max(float a, float b) {
  return a < b ? b : a;
}
inline float lf_dot(float3 a, float3 b) {
  return (a.x * b.x + a.y * b.y) + a.z * b.z;
}
inline float3 lf_rows(float4 r0, float4 r1, float4 r2, float3 p) {
  return (float3)(lf_dot(r0.xyz, p), lf_dot(r1.xyz, p), lf_dot(r2.xyz, p));
}
inline float3 lf_cross(float3 x, float3 y) {
  return (float3)(x.y * y.z - y.y * x.z, x.z * y.x - y.z * x.x, x.x * y.y - y.x * x.y);
}

/* light_frame.cpp clip_near: Sutherland-Hodgman against z >= z_min; returns the corner count (<= 4). */
inline int lf_clip_near(const float3* tri, float z_min, float3* out) {
  int n = 0;
  for (int e = 0; e < 3; ++e) {
    const float3 a = tri[e], b = tri[(e + 1) % 3];
    const bool ina = a.z >= z_min, inb = b.z >= z_min;
    if (ina) out[n++] = a;
    if (ina != inb) out[n++] = a + (b - a) * ((z_min - a.z) / (b.z - a.z));
  }
  return n;
}

/* LightFitParams (voxr_layout.h) as vectors. */
typedef struct LightFit {
  float4 receivers_lo, receivers_hi, row0, row1, row2, light;
  uint projective, point;
  float eps, depth_floor;
} LightFit;

inline LightFit lf_fit(const LightFitParams a) {
  LightFit f;
  f.receivers_lo = vload4(0, a.receivers_lo);
  f.receivers_hi = vload4(0, a.receivers_hi);
  f.row0 = vload4(0, a.row0);
  f.row1 = vload4(0, a.row1);
  f.row2 = vload4(0, a.row2);
  f.light = vload4(0, a.light);
  f.projective = a.projective;
  f.point = a.point;
  f.eps = a.eps;
  f.depth_floor = a.depth_floor;
  return f;
}

/* fit_light_frame's per-caster work: whether triangle (a, b, c) can shadow a corner of the receivers' box
 * (casts_on) and, if so, its light-space box (lo.xy, hi.xy) and nearest depth. Returns 0 for a triangle that
 * casts nothing or lies wholly behind the near cut. */
inline int lf_caster(const LightFit* f, float3 a, float3 b, float3 c, float4* box, float* near) {
  const float3 n = lf_cross(b - a, c - a);
  const float len = sqrt(lf_dot(n, n));
  if (!(len > 0.0f)) return 0;
  const float3 u = n / len;
  const float light_side = f->point ? lf_dot(u, f->light.xyz - a) : -lf_dot(u, f->light.xyz);
  bool casts = false;
  for (int i = 0; i < 8 && !casts; ++i) {
    const float3 k = (float3)((i & 1) ? f->receivers_hi.x : f->receivers_lo.x,
                              (i & 2) ? f->receivers_hi.y : f->receivers_lo.y,
                              (i & 4) ? f->receivers_hi.z : f->receivers_lo.z);
    const float d = lf_dot(u, k - a);
    casts = (light_side >= 0.0f && d < -f->eps) || (light_side <= 0.0f && d > f->eps);
  }
  if (!casts) return 0;
  float3 front[4];
  int n_front = 3;
  if (!f->projective) {
    front[0] = a;
    front[1] = b;
    front[2] = c;
  } else {
    const float3 L = f->light.xyz;
    const float3 view[3] = {lf_rows(f->row0, f->row1, f->row2, a - L),
                            lf_rows(f->row0, f->row1, f->row2, b - L),
                            lf_rows(f->row0, f->row1, f->row2, c - L)};
    n_front = lf_clip_near(view, f->depth_floor, front);
    for (int i = 0; i < n_front; ++i) { /* back to world: transpose(rows) x corner + light */
      const float3 q = front[i];
      front[i] = ((f->row0.xyz * q.x + f->row1.xyz * q.y) + f->row2.xyz * q.z) + L;
    }
  }
  float4 bx = (float4)(INFINITY, INFINITY, -INFINITY, -INFINITY);
  float nz = INFINITY;
  for (int i = 0; i < n_front; ++i) {
    float3 q;
    if (!f->projective) {
      q = lf_rows(f->row0, f->row1, f->row2, front[i]);
    } else {
      const float3 v = lf_rows(f->row0, f->row1, f->row2, front[i] - f->light.xyz);
      q = (float3)(v.x / v.z, v.y / v.z, v.z);
    }
    bx = (float4)(lf_min(bx.x, q.x), lf_min(bx.y, q.y), lf_max(bx.z, q.x), lf_max(bx.w, q.y));
    nz = lf_min(nz, q.z);
  }
  if (bx.x > bx.z || bx.y > bx.w) return 0;
  *box = bx;
  *near = nz;
  return 1;
}

inline void lf_corners(__global const float4* positions, __global const uint4* triangles, uint t, float3* a,
                       float3* b, float3* c, uint* material) {
  const uint4 tri = triangles[t];
  *a = positions[tri.x].xyz;
  *b = positions[tri.y].xyz;
  *c = positions[tri.z].xyz;
  *material = tri.w;
}

__kernel void light_reduce_init(__global uint* reduce) {
  if (get_global_id(0) != 0) return;
  for (int s = 0; s < 2; ++s) {
    reduce[LIGHT_CAST + s] = lf_key(INFINITY);
    reduce[LIGHT_CAST + 2 + s] = lf_key(-INFINITY);
  }
  reduce[LIGHT_NEAR] = lf_key(INFINITY);
  for (int a = 0; a < 3; ++a) {
    reduce[LIGHT_BOUNDS + a] = lf_key(FLT_MAX);
    reduce[LIGHT_BOUNDS + 3 + a] = lf_key(-FLT_MAX);
  }
  reduce[LIGHT_SPLIT] = 0;
  reduce[LIGHT_OVERFLOW] = 0;
}

/* Work-group reduction of `n` (<= 6) ordered keys into `reduce` from `first_slot`: slot s takes the minimum
 * when bit s of `max_mask` is clear, else the maximum; a tree over local memory (WG_SIZE a power of two),
 * then one global atomic per slot and group. Every work item of the group calls it (barriers). */
inline void lf_group_reduce(__local uint* scratch, const uint* keys, int n, uint max_mask, bool has,
                            __global uint* reduce, int first_slot) {
  const uint lid = get_local_id(0);
  for (int s = 0; s < n; ++s)
    scratch[s * WG_SIZE + lid] = has ? keys[s] : (((max_mask >> s) & 1) ? 0u : 0xffffffffu);
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint stride = WG_SIZE / 2; stride > 0; stride >>= 1) {
    if (lid < stride)
      for (int s = 0; s < n; ++s) {
        const uint x = scratch[s * WG_SIZE + lid], y = scratch[s * WG_SIZE + lid + stride];
        scratch[s * WG_SIZE + lid] = ((max_mask >> s) & 1) ? max(x, y) : min(x, y);
      }
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (lid == 0)
    for (int s = 0; s < n; ++s) {
      const uint v = scratch[s * WG_SIZE];
      if ((max_mask >> s) & 1) {
        if (v != 0u) atomic_max(&reduce[first_slot + s], v);
      } else if (v != 0xffffffffu) {
        atomic_min(&reduce[first_slot + s], v);
      }
    }
}

/* Pass 0 of the fit: each caster's box and nearest depth (box.x = +inf: no caster) for pass 1, and the
 * casters' footprint. */
__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void light_fit_casters(
    LightFitParams fit_params, __global const float4* positions, __global const uint4* triangles, uint count,
    __global float4* boxes, __global float* nears, __global uint* reduce) {
  __local uint slots[4 * WG_SIZE];
  const LightFit fit = lf_fit(fit_params);
  const uint t = get_global_id(0);
  float4 box = (float4)(INFINITY, INFINITY, -INFINITY, -INFINITY);
  float near = INFINITY;
  bool has = false;
  if (t < count) {
    float3 a, b, c;
    uint material;
    lf_corners(positions, triangles, t, &a, &b, &c, &material);
    has = lf_caster(&fit, a, b, c, &box, &near);
    boxes[t] = has ? box : (float4)(INFINITY, INFINITY, -INFINITY, -INFINITY);
    nears[t] = near;
  }
  const uint keys[4] = {lf_key(box.x), lf_key(box.y), lf_key(box.z), lf_key(box.w)};
  lf_group_reduce(slots, keys, 4, 0xcu, has, reduce, LIGHT_CAST);
}

/* Pass 1: the nearest depth of the casters whose box overlaps the footprint; `receiving`: the receivers'
 * columns (lo.xy, hi.xy). */
__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void light_fit_near(
    float4 receiving, __global const float4* boxes, __global const float* nears, uint count,
    __global uint* reduce) {
  __local uint slots[WG_SIZE];
  const uint t = get_global_id(0);
  bool has = false;
  float near = INFINITY;
  if (t < count) {
    /* The footprint as fit_light_frame cuts it. */
    const float4 casting = (float4)(lf_value(reduce[LIGHT_CAST + 0]), lf_value(reduce[LIGHT_CAST + 1]),
                                    lf_value(reduce[LIGHT_CAST + 2]), lf_value(reduce[LIGHT_CAST + 3]));
    float4 fp = receiving;
    const bool casting_empty = casting.x > casting.z || casting.y > casting.w;
    const bool overlap = receiving.x <= casting.z && casting.x <= receiving.z && receiving.y <= casting.w &&
                         casting.y <= receiving.w;
    if (!casting_empty && overlap)
      fp = (float4)(lf_max(receiving.x, casting.x), lf_max(receiving.y, casting.y),
                    lf_min(receiving.z, casting.z), lf_min(receiving.w, casting.w));
    const float4 box = boxes[t];
    near = nears[t];
    has = box.x <= box.z && box.x <= fp.z && fp.x <= box.z && box.y <= fp.w && fp.y <= box.w;
  }
  const uint keys[1] = {lf_key(near)};
  lf_group_reduce(slots, keys, 1, 0u, has, reduce, LIGHT_NEAR);
}

/* LightPiecesParams (voxr_layout.h) as vectors. */
typedef struct LightPieces {
  float4 m0, m1, m2, view0, view1, view2, light, dims;
  float z_min;
  uint projective, write;
} LightPieces;

inline LightPieces lf_pieces(const LightPiecesParams a) {
  LightPieces p;
  p.m0 = vload4(0, a.m0);
  p.m1 = vload4(0, a.m1);
  p.m2 = vload4(0, a.m2);
  p.view0 = vload4(0, a.view0);
  p.view1 = vload4(0, a.view1);
  p.view2 = vload4(0, a.view2);
  p.light = vload4(0, a.light);
  p.dims = vload4(0, a.dims);
  p.z_min = a.z_min;
  p.projective = a.projective;
  p.write = a.write;
  return p;
}

inline float3 lf_grid(const LightPieces* p, float3 w) {
  return (float3)(((p->m0.x * w.x + p->m0.y * w.y) + p->m0.z * w.z) + p->m0.w,
                  ((p->m1.x * w.x + p->m1.y * w.y) + p->m1.z * w.z) + p->m1.w,
                  ((p->m2.x * w.x + p->m2.y * w.y) + p->m2.z * w.z) + p->m2.w);
}

inline float3 lf_project(const ShadowFrame* f, float3 q) {
  return (float3)((q.x / q.z - f->u0) * f->inv_du, (q.y / q.z - f->v0) * f->inv_dv,
                  (f->inv_near - 1.0f / q.z) * f->depth_scale);
}

/* Grid-unit box of a triangle's corners. */
inline void lf_box(const LightPieces* p, const float3* w, float3* lo, float3* hi) {
  *lo = (float3)(FLT_MAX);
  *hi = (float3)(-FLT_MAX);
  for (int c = 0; c < 3; ++c) {
    const float3 g = lf_grid(p, w[c]);
    *lo = (float3)(lf_min(lo->x, g.x), lf_min(lo->y, g.y), lf_min(lo->z, g.z));
    *hi = (float3)(lf_max(hi->x, g.x), lf_max(hi->y, g.y), lf_max(hi->z, g.z));
  }
}

inline void lf_emit(const LightPieces* p, const float3* w, uint material, ulong at, ulong capacity,
                    __global float4* out_positions, __global uint4* out_triangles) {
  /* The capacity is pass 0's scanned total, so `at` stays below it; the check only bounds the write. */
  if (!p->write || at >= capacity) return;
  for (int c = 0; c < 3; ++c) out_positions[3 * at + c] = (float4)(w[c], 1.0f);
  const uint v = (uint)(3 * at);
  out_triangles[at] = (uint4)(v, v + 1, v + 2, material);
}

/* The piece of `tri` at `depth` levels down the 4-ary split tree along `path` (2 bits per level, level 0
 * lowest): the host's recursion's midpoints, recomputed from the root (same floats). */
inline void lf_piece(const float3* tri, uint path, int depth, float3* w) {
  w[0] = tri[0];
  w[1] = tri[1];
  w[2] = tri[2];
  for (int l = 0; l < depth; ++l) {
    const float3 ab = 0.5f * (w[0] + w[1]), bc = 0.5f * (w[1] + w[2]), ca = 0.5f * (w[2] + w[0]);
    switch ((path >> (2 * l)) & 3u) {
      case 0:
        w[1] = ab;
        w[2] = ca;
        break;
      case 1:
        w[0] = ab;
        w[2] = bc;
        break;
      case 2:
        w[0] = ca;
        w[1] = bc;
        break;
      default:
        w[0] = ab;
        w[1] = bc;
        w[2] = ca;
        break;
    }
  }
}

/* split_oversized_triangles (kGrid) for one triangle: itself when no longer than LIGHT_SPLIT_EXTENT voxels,
 * else its edge-midpoint pieces, depth first, dropping pieces that miss the grid. Returns the pieces written
 * (or counted) from `at`. */
inline uint lf_split(const LightPieces* p, const float3* tri, uint material, ulong at, ulong capacity,
                     __global float4* out_positions, __global uint4* out_triangles, __global uint* reduce) {
  float3 lo, hi;
  lf_box(p, tri, &lo, &hi);
  const float3 e = hi - lo;
  if (lf_max(lf_max(e.x, e.y), e.z) <= LIGHT_SPLIT_EXTENT) { /* needs_work is false */
    lf_emit(p, tri, material, at, capacity, out_positions, out_triangles);
    return 1;
  }
  if (!p->write) atomic_inc(&reduce[LIGHT_SPLIT]);
  uint pieces = 0, path = 0;
  int depth = 0;
  for (;;) {
    float3 w[3];
    lf_piece(tri, path, depth, w);
    lf_box(p, w, &lo, &hi);
    bool descend = false;
    if (!(hi.x < -1.0f || lo.x > p->dims.x + 1.0f || hi.y < -1.0f || lo.y > p->dims.y + 1.0f ||
          hi.z < -1.0f || lo.z > p->dims.z + 1.0f)) { /* else it misses the grid */
      const float3 x = hi - lo;
      if (lf_max(lf_max(x.x, x.y), x.z) <= LIGHT_SPLIT_EXTENT) {
        lf_emit(p, w, material, at + pieces, capacity, out_positions, out_triangles);
        ++pieces;
      } else if (depth == LIGHT_SPLIT_DEPTH) {
        if (!p->write) atomic_inc(&reduce[LIGHT_OVERFLOW]);
      } else {
        descend = true;
      }
    }
    if (descend) { /* first child */
      path &= ~(3u << (2 * depth));
      ++depth;
      continue;
    }
    /* next sibling, climbing past last children */
    while (depth > 0 && ((path >> (2 * (depth - 1))) & 3u) == 3u) --depth;
    if (depth == 0) break;
    path += 1u << (2 * (depth - 1));
  }
  return pieces;
}

/* Point light: every vertex in the light's view and, in front of the near clip, in grid units (w = 1;
 * behind it w = 0), once, as project_to_light_grid does. */
__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void light_vertices(
    LightPiecesParams params, ShadowFrame frame, __global const float4* positions, uint count,
    __global float4* projected) {
  const LightPieces p = lf_pieces(params);
  const uint v = get_global_id(0);
  if (v >= count) return;
  const float3 q = lf_rows(p.view0, p.view1, p.view2, positions[v].xyz - p.light.xyz);
  projected[v] = q.z >= p.z_min ? (float4)(lf_project(&frame, q), 1.0f) : (float4)(0.0f);
}

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void light_pieces(
    LightPiecesParams params, ShadowFrame frame, __global const float4* positions,
    __global const uint4* triangles, __global const float4* projected, uint count, __global uint* counts,
    __global const ulong* offsets, ulong capacity, __global float4* out_positions,
    __global uint4* out_triangles, __global uint* reduce) {
  __local uint slots[6 * WG_SIZE];
  const LightPieces p = lf_pieces(params);
  const uint t = get_global_id(0);
  float3 lo = (float3)(FLT_MAX), hi = (float3)(-FLT_MAX);
  bool survived = false;
  if (t < count) {
    const uint4 corner = triangles[t];
    const uint material = corner.w;
    const ulong at = p.write ? offsets[t] : 0;
    uint pieces = 0;
    if (!p.projective) {
      const float3 tri[3] = {positions[corner.x].xyz, positions[corner.y].xyz, positions[corner.z].xyz};
      pieces = lf_split(&p, tri, material, at, capacity, out_positions, out_triangles, reduce);
    } else {
      /* project_to_light_grid: into the light's view, clipped at z_min, into grid units, culled. */
      const float4 gv[3] = {projected[corner.x], projected[corner.y], projected[corner.z]};
      const int in_front = (int)(gv[0].w) + (int)(gv[1].w) + (int)(gv[2].w);
      if (in_front > 0) {
        float3 g[4];
        int n = 3;
        if (in_front == 3) {
          for (int k = 0; k < 3; ++k) g[k] = gv[k].xyz;
        } else {
          const float3 L = p.light.xyz;
          const float3 q[3] = {lf_rows(p.view0, p.view1, p.view2, positions[corner.x].xyz - L),
                               lf_rows(p.view0, p.view1, p.view2, positions[corner.y].xyz - L),
                               lf_rows(p.view0, p.view1, p.view2, positions[corner.z].xyz - L)};
          float3 clipped[4];
          n = lf_clip_near(q, p.z_min, clipped);
          for (int k = 0; k < n; ++k) g[k] = lf_project(&frame, clipped[k]);
        }
        bool outside = false;
        for (int axis = 0; axis < 3 && !outside; ++axis) {
          const float d = axis == 0 ? p.dims.x : axis == 1 ? p.dims.y : p.dims.z;
          bool below = true, above = true;
          for (int k = 0; k < n; ++k) {
            const float v = axis == 0 ? g[k].x : axis == 1 ? g[k].y : g[k].z;
            below = below && v < 0.0f;
            above = above && v > d;
          }
          outside = below || above;
        }
        if (!outside) {
          survived = true;
          for (int k = 0; k < n; ++k) {
            lo = (float3)(lf_min(lo.x, g[k].x), lf_min(lo.y, g[k].y), lf_min(lo.z, g[k].z));
            hi = (float3)(lf_max(hi.x, g[k].x), lf_max(hi.y, g[k].y), lf_max(hi.z, g[k].z));
          }
          for (int k = 1; k + 1 < n; ++k) {
            const float3 tri[3] = {g[0], g[k], g[k + 1]};
            pieces +=
                lf_split(&p, tri, material, at + pieces, capacity, out_positions, out_triangles, reduce);
          }
        }
      }
    }
    if (!p.write) counts[t] = pieces;
  }
  if (p.write || !p.projective) return; /* uniform across the launch: no work item waits at a barrier */
  const uint keys[6] = {lf_key(lo.x), lf_key(lo.y), lf_key(lo.z), lf_key(hi.x), lf_key(hi.y), lf_key(hi.z)};
  lf_group_reduce(slots, keys, 6, 0x38u, survived, reduce, LIGHT_BOUNDS);
}
