/* triangle_grid.h — how a kernel reads the per-voxel triangle lists (host/render/triangle_grid.h) and finds
 * the exact nearest hit of a ray through them: the one place both exact methods (refraction and shadows
 * `voxel-exact`) intersect the scene. A kernel declares VOXR_TRIANGLE_GRID_PARAMS among its parameters (the
 * host passes TriangleGrid::view_args()) and builds its view with VOXR_TRIANGLE_GRID():
 *
 *   __kernel void k(VOXR_TRIANGLE_GRID_PARAMS, __global const RenderMaterial* materials, ...) {
 *     const TriangleGridView tg = VOXR_TRIANGLE_GRID();
 *     TgHit hit;
 *     if (tg_nearest_hit(&tg, origin, dir, 0.0f, INFINITY, skip, materials, 1e-6f, &hit)) ...
 *   }
 *
 * Lists: voxel of rank r holds the mesh indices ids[offsets[r] .. offsets[r + 1]), ascending; a list reaching
 * past `capacity` was not filled (a frame whose pair count outgrew its capacity is rendered again). Rays and
 * hits are in the mesh's frame (anchor-relative world); the grid's affine maps a ray to grid units with the
 * same parameter t. */
#ifndef TRIANGLE_GRID_H
#define TRIANGLE_GRID_H

#include "grid_view.h"
#include "voxr_layout.h"

#pragma OPENCL FP_CONTRACT OFF

#define VOXR_TRIANGLE_GRID_PARAMS                                                               \
  VOXR_GRID_VIEW_PARAMS, __global const ulong *tg_buf_offsets, __global const uint *tg_buf_ids, \
      ulong tg_list_capacity, __global const float4 *tg_buf_positions,                          \
      __global const uint4 *tg_buf_triangles, __global const uint *tg_buf_bricks, uint4 tg_brick_dims
#define VOXR_TRIANGLE_GRID()                                                                            \
  tg_make(&gv_params, VOXR_GRID_VIEW(), tg_buf_offsets, tg_buf_ids, tg_list_capacity, tg_buf_positions, \
          tg_buf_triangles, tg_buf_bricks, tg_brick_dims)

typedef struct TriangleGridView {
  GridView grid;
  float4 to_grid[3]; /* rows of the world -> grid affine */
  __global const ulong* offsets;
  __global const uint* ids;
  ulong capacity;
  __global const float4* positions;
  __global const uint4* triangles;
  __global const uint* bricks; /* one bit per VOXR_BRICK^3 voxels, set where one is occupied */
  uint brick_x, brick_y;       /* bricks along x and y */
} TriangleGridView;

inline TriangleGridView tg_make(const VoxGridView* p, GridView grid, __global const ulong* offsets,
                                __global const uint* ids, ulong capacity, __global const float4* positions,
                                __global const uint4* triangles, __global const uint* bricks,
                                uint4 brick_dims) {
  TriangleGridView tg;
  tg.grid = grid;
  const float* m = p->world_to_grid;
  for (int r = 0; r < 3; ++r) tg.to_grid[r] = (float4)(m[4 * r], m[4 * r + 1], m[4 * r + 2], m[4 * r + 3]);
  tg.offsets = offsets;
  tg.ids = ids;
  tg.capacity = capacity;
  tg.positions = positions;
  tg.triangles = triangles;
  tg.bricks = bricks;
  tg.brick_x = brick_dims.x;
  tg.brick_y = brick_dims.y;
  return tg;
}

/* ---- watertight ray/triangle intersection (Woop, Benthin & Wald, JCGT 2(1) 2013) ---------------------- */

/* The ray's shear to the frame where it runs along +z: the axis of |dir|'s largest component becomes z,
 * the other two are swapped when that component is negative (keeping the winding). */
typedef struct TgRay {
  float3 org;
  int kx, ky, kz;
  float sx, sy, sz;
} TgRay;

inline float tg_axis(float3 v, int a) {
  return a == 0 ? v.x : a == 1 ? v.y : v.z;
}

inline TgRay tg_ray(float3 org, float3 dir) {
  TgRay r;
  r.org = org;
  const float3 a = fabs(dir);
  r.kz = a.x >= a.y && a.x >= a.z ? 0 : a.y >= a.z ? 1 : 2;
  r.kx = r.kz == 2 ? 0 : r.kz + 1;
  r.ky = r.kx == 2 ? 0 : r.kx + 1;
  if (tg_axis(dir, r.kz) < 0.0f) {
    const int s = r.kx;
    r.kx = r.ky;
    r.ky = s;
  }
  const float dz = tg_axis(dir, r.kz);
  r.sx = tg_axis(dir, r.kx) / dz;
  r.sy = tg_axis(dir, r.ky) / dz;
  r.sz = 1.0f / dz;
  return r;
}

/* Whether the ray meets triangle (a, b, c) at a parameter in [t_min, t_max]: *t, and the barycentric
 * weights *b1, *b2 of b and c (Embree's u, v). Watertight: a ray through a shared edge or vertex meets at
 * least one of the triangles there (the edge functions are evaluated in one order for both; the paper's
 * double-precision fallback for an exactly zero edge function is not taken: such a ray counts as on the
 * edge). Both sides count (no culling); degenerate triangles (zero determinant) are missed. */
inline int tg_intersect(const TgRay* r, float3 a, float3 b, float3 c, float t_min, float t_max, float* t,
                        float* b1, float* b2) {
  const float3 A = a - r->org, B = b - r->org, C = c - r->org;
  const float az = tg_axis(A, r->kz), bz = tg_axis(B, r->kz), cz = tg_axis(C, r->kz);
  const float ax = tg_axis(A, r->kx) - r->sx * az, ay = tg_axis(A, r->ky) - r->sy * az;
  const float bx = tg_axis(B, r->kx) - r->sx * bz, by = tg_axis(B, r->ky) - r->sy * bz;
  const float cx = tg_axis(C, r->kx) - r->sx * cz, cy = tg_axis(C, r->ky) - r->sy * cz;
  const float u = cx * by - cy * bx;
  const float v = ax * cy - ay * cx;
  const float w = bx * ay - by * ax;
  if ((u < 0.0f || v < 0.0f || w < 0.0f) && (u > 0.0f || v > 0.0f || w > 0.0f)) return 0;
  const float det = u + v + w;
  if (det == 0.0f) return 0;
  const float tt = (u * (r->sz * az) + v * (r->sz * bz)) + w * (r->sz * cz);
  const float inv = 1.0f / det;
  const float th = tt * inv;
  if (!(th >= t_min && th <= t_max)) return 0;
  *t = th;
  *b1 = v * inv;
  *b2 = w * inv;
  return 1;
}

/* ---- empty space ---------------------------------------------------------------------------------- */

inline int tg_brick_empty(const TriangleGridView* tg, int i, int j, int k) {
  const ulong b =
      ((ulong)(k / VOXR_BRICK) * tg->brick_y + (uint)(j / VOXR_BRICK)) * tg->brick_x + (uint)(i / VOXR_BRICK);
  return ((tg->bricks[b >> 5] >> (uint)(b & 31)) & 1u) == 0u;
}

/* In an empty brick, moves the walk to the voxel just past the brick's exit along the ray og + t dg (grid
 * units; a ten-thousandth of a voxel beyond it, far inside the lists' conservative widening, so no listed
 * triangle is passed). Returns 0 when that point leaves the grid; the walk is unchanged (and the caller
 * steps on voxel by voxel) when rounding keeps the point in the same brick. */
inline int tg_skip_brick(GvRay* walk, const GridView* g, float3 og, float3 dg) {
  const int bi = walk->i / VOXR_BRICK * VOXR_BRICK, bj = walk->j / VOXR_BRICK * VOXR_BRICK;
  const int bk = walk->k / VOXR_BRICK * VOXR_BRICK;
  float t = INFINITY;
  if (walk->si != 0) t = fmin(t, ((float)(walk->si > 0 ? bi + VOXR_BRICK : bi) - og.x) / dg.x);
  if (walk->sj != 0) t = fmin(t, ((float)(walk->sj > 0 ? bj + VOXR_BRICK : bj) - og.y) / dg.y);
  if (walk->sk != 0) t = fmin(t, ((float)(walk->sk > 0 ? bk + VOXR_BRICK : bk) - og.z) / dg.z);
  t += 1.0e-4f / length(dg);
  if (!(t > walk->t)) return 1;
  const float3 p = og + t * dg;
  const int i = (int)floor(p.x), j = (int)floor(p.y), k = (int)floor(p.z);
  if (!gv_contains(g, i, j, k)) return 0;
  if (i / VOXR_BRICK * VOXR_BRICK == bi && j / VOXR_BRICK * VOXR_BRICK == bj &&
      k / VOXR_BRICK * VOXR_BRICK == bk)
    return 1;
  walk->i = i;
  walk->j = j;
  walk->k = k;
  gv_ray_steps(walk, og, dg, (float3)(1.0f) / dg);
  walk->t = t;
  return 2;
}

/* ---- nearest hit through the lists ----------------------------------------------------------------- */

typedef struct TgHit {
  float t;       /* ray parameter (world units for a unit direction) */
  float b1, b2;  /* barycentric weights of the triangle's vertices 1 and 2 */
  uint triangle; /* mesh index; VOXR_NO_TRIANGLE when nothing was hit */
  uint material; /* the triangle's material id */
  int opaque;    /* its material is opaque */
  int enters;    /* the ray meets its front (its winding faces the ray) */
} TgHit;

/* Fills the rest of candidate hit *c on triangle `id` (vertices p0, p1, p2, material tri.w) of a ray along
 * dir: which triangle, its material, whether opaque, whether the ray enters it. */
inline void tg_classify(TgHit* c, uint id, uint4 tri, float3 p0, float3 p1, float3 p2, float3 dir,
                        __global const RenderMaterial* materials) {
  c->triangle = id;
  c->material = tri.w;
  c->opaque = materials[tri.w].kind == VOXR_MATERIAL_OPAQUE;
  c->enters = dot(cross(p1 - p0, p2 - p0), dir) < 0.0f;
}

/* Whether hit c beats the best so far: nearer by more than `coincide`; within it (coincident surfaces, e.g. a
 * glass face standing on a floor, which rounding orders either way) an opaque surface before a dielectric or
 * sheet, of two opaque ones the nearer, then the lower id; of dielectrics and sheets one the ray enters
 * before one it leaves (glass to water at a shared face is one interface, not glass to air to water), then
 * the lower id: the reference's rule where surfaces touch (ReferenceScene::intersect). */
inline int tg_better(const TgHit* c, const TgHit* best, float coincide) {
  if (best->triangle == VOXR_NO_TRIANGLE) return 1;
  if (c->t < best->t - coincide) return 1;
  if (c->t > best->t + coincide) return 0;
  if (c->opaque != best->opaque) return c->opaque > best->opaque;
  if (c->opaque && c->t != best->t) return c->t < best->t;
  if (!c->opaque && c->enters != best->enters) return c->enters > best->enters;
  return c->triangle < best->triangle;
}

/* Whether triangle `a` shares a vertex index with `b`. */
inline int tg_shares_vertex(uint4 a, uint4 b) {
  return a.x == b.x || a.x == b.y || a.x == b.z || a.y == b.x || a.y == b.y || a.y == b.z || a.z == b.x ||
         a.z == b.y || a.z == b.z;
}

/* The nearest hit of origin + t dir, t in [t_min, t_max], over the triangles the grid lists, for a ray
 * leaving the triangles leaving[0 .. leaving_count) (the surface it left and coincident ones it passed
 * there; at most 8): those are skipped at any t, and triangles sharing a vertex with one of them are skipped
 * below t = `neighbour_t` (the same surface at a shared edge or vertex, which a rounded origin may lie a
 * hair beyond). The grid is walked voxel by voxel (gv_ray_*) from the origin; each occupied voxel's
 * triangles are tested (tg_intersect), and the march ends at the first voxel whose exit lies beyond the best
 * hit so far (plus `coincide` and a thousandth of a voxel): conservative lists hold every triangle that
 * touches a voxel, so no nearer hit can lie further on (a hit behind the origin, t_min < 0, lies on a
 * triangle touching the first voxel). Hits within `coincide` (t units) of each other are ordered by
 * tg_better. materials: RenderMaterial by material id. Returns whether a hit was found (*hit; its triangle
 * is VOXR_NO_TRIANGLE otherwise). */
inline int tg_nearest_hit_leaving(const TriangleGridView* tg, float3 origin, float3 dir, float t_min,
                                  float t_max, const uint* leaving, uint leaving_count, float neighbour_t,
                                  __global const RenderMaterial* materials, float coincide, TgHit* hit) {
  hit->triangle = VOXR_NO_TRIANGLE;
  hit->t = INFINITY;
  hit->b1 = hit->b2 = 0.0f;
  hit->material = 0;
  hit->opaque = 0;
  hit->enters = 0;
  const float3 og = (float3)(dot(tg->to_grid[0].xyz, origin) + tg->to_grid[0].w,
                             dot(tg->to_grid[1].xyz, origin) + tg->to_grid[1].w,
                             dot(tg->to_grid[2].xyz, origin) + tg->to_grid[2].w);
  const float3 dg =
      (float3)(dot(tg->to_grid[0].xyz, dir), dot(tg->to_grid[1].xyz, dir), dot(tg->to_grid[2].xyz, dir));
  const float slack = 1.0e-3f / length(dg); /* a thousandth of a voxel in t */
  GvRay walk;
  if (!gv_ray_begin(&walk, &tg->grid, og, dg)) return 0;
  const TgRay ray = tg_ray(origin, dir);
  const uint max_steps = 3u * (tg->grid.dims_x + tg->grid.dims_y + tg->grid.dims_z);
  for (uint step = 0; step < max_steps; ++step) {
    if (walk.t > t_max) break;
    const ulong v = gv_linear(&tg->grid, walk.i, walk.j, walk.k);
    if (!gv_occupied(&tg->grid, v)) {
      if (hit->triangle == VOXR_NO_TRIANGLE && tg_brick_empty(tg, walk.i, walk.j, walk.k)) {
        const int skipped = tg_skip_brick(&walk, &tg->grid, og, dg);
        if (skipped == 0) break;
        if (skipped == 2) continue;
      }
    } else {
      const uint rank = gv_rank(&tg->grid, v);
      if (rank < tg->grid.voxels_set) {
        const ulong first = tg->offsets[rank], end = tg->offsets[rank + 1];
        if (end <= tg->capacity) {
          for (ulong e = first; e < end; ++e) {
            const uint id = tg->ids[e];
            int left = 0;
            for (uint l = 0; l < leaving_count; ++l) left |= id == leaving[l];
            if (left) continue;
            const uint4 tri = tg->triangles[id];
            const float3 p0 = tg->positions[tri.x].xyz, p1 = tg->positions[tri.y].xyz,
                         p2 = tg->positions[tri.z].xyz;
            TgHit c;
            if (!tg_intersect(&ray, p0, p1, p2, t_min, t_max, &c.t, &c.b1, &c.b2)) continue;
            if (c.t < neighbour_t) {
              int neighbour = 0;
              for (uint l = 0; l < leaving_count; ++l)
                neighbour |= tg_shares_vertex(tri, tg->triangles[leaving[l]]);
              if (neighbour) continue;
            }
            tg_classify(&c, id, tri, p0, p1, p2, dir, materials);
            if (tg_better(&c, hit, coincide)) *hit = c;
          }
        }
      }
    }
    const float t_out = fmin(fmin(walk.tx, walk.ty), walk.tz);
    if (hit->triangle != VOXR_NO_TRIANGLE && hit->t + coincide <= t_out + slack) return 1;
    if (gv_ray_step(&walk, &tg->grid) < 0) break;
  }
  return hit->triangle != VOXR_NO_TRIANGLE;
}

/* tg_nearest_hit_leaving for a ray that leaves one triangle, `skip` (VOXR_NO_TRIANGLE: none), skipped at
 * any t and nothing else: no distance epsilon. */
inline int tg_nearest_hit(const TriangleGridView* tg, float3 origin, float3 dir, float t_min, float t_max,
                          uint skip, __global const RenderMaterial* materials, float coincide, TgHit* hit) {
  const uint leaving[1] = {skip};
  return tg_nearest_hit_leaving(tg, origin, dir, t_min, t_max, leaving, skip != VOXR_NO_TRIANGLE ? 1u : 0u,
                                -INFINITY, materials, coincide, hit);
}

#endif
