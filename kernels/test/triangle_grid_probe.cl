/* triangle_grid_probe.cl — test kernels for kernels/common/triangle_grid.h: per ray, the nearest hit
 * through the lists (tg_nearest_hit) and by brute force over every triangle with the same intersection test
 * and order (tg_intersect, tg_better), which must agree bit for bit.
 * in:  rays (origin, t_min), directions (dir, t_max), the triangle each ray skips
 * out: per ray the hit triangle (VOXR_NO_TRIANGLE: none) and (t, b1, b2, 0)
 * shape: one work item per ray. */
#include "triangle_grid.h"

#ifndef WG_SIZE
#define WG_SIZE 64
#endif

inline void tg_probe_store(const TgHit* h, uint ray, __global uint* tri, __global float4* th) {
  tri[ray] = h->triangle;
  th[ray] = (float4)(h->t, h->b1, h->b2, 0.0f);
}

/* rays: origin (xyz) and t_min (w); dirs: direction (xyz) and t_max (w); skip: per ray. */
__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void tg_probe_grid(
    VOXR_TRIANGLE_GRID_PARAMS, __global const RenderMaterial* materials, __global const float4* rays,
    __global const float4* dirs, __global const uint* skip, uint count, float coincide, __global uint* tri,
    __global float4* th) {
  const uint ray = get_global_id(0);
  if (ray >= count) return;
  const TriangleGridView tg = VOXR_TRIANGLE_GRID();
  TgHit hit;
  tg_nearest_hit(&tg, rays[ray].xyz, dirs[ray].xyz, rays[ray].w, dirs[ray].w, skip[ray], materials, coincide,
                 &hit);
  tg_probe_store(&hit, ray, tri, th);
}

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void tg_probe_all(
    __global const float4* positions, __global const uint4* triangles, uint triangle_count,
    __global const RenderMaterial* materials, __global const float4* rays, __global const float4* dirs,
    __global const uint* skip, uint count, float coincide, __global uint* tri, __global float4* th) {
  const uint ray = get_global_id(0);
  if (ray >= count) return;
  const TgRay r = tg_ray(rays[ray].xyz, dirs[ray].xyz);
  TgHit best;
  best.triangle = VOXR_NO_TRIANGLE;
  best.t = INFINITY;
  best.b1 = best.b2 = 0.0f;
  for (uint id = 0; id < triangle_count; ++id) {
    if (id == skip[ray]) continue;
    const uint4 t = triangles[id];
    const float3 p0 = positions[t.x].xyz, p1 = positions[t.y].xyz, p2 = positions[t.z].xyz;
    TgHit c;
    if (!tg_intersect(&r, p0, p1, p2, rays[ray].w, dirs[ray].w, &c.t, &c.b1, &c.b2)) continue;
    tg_classify(&c, id, t, p0, p1, p2, dirs[ray].xyz, materials);
    if (tg_better(&c, &best, coincide)) best = c;
  }
  tg_probe_store(&best, ray, tri, th);
}
