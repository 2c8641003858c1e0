/* grid_view_probe.cl — reads a DeviceVoxelGrid through grid_view.h and writes what every accessor returns,
 * so tests/grid_view_test.cpp can compare it with the grid read back to the host and with a CPU traversal.
 *
 * grid_view_fetch: for each query voxel (query[q].xyz = i, j, k; outside the grid gives all zeros):
 *   flags[q]     bit 0 occupied, bit 1 inside
 *   rank[q]      gv_rank, or ~0 when the voxel is not occupied or the grid has no rank index
 *   count[q], material[q], normal[3q .. 3q+2]   the sparse channels at that rank (0 when not occupied)
 *   shape: one work item per query, n queries.
 *
 * grid_view_march: for each ray (rays[2r] = origin, rays[2r+1] = direction, xyz in grid units, w unused)
 * walks gv_ray_begin / gv_ray_step until the ray leaves the grid or max_voxels voxels were visited:
 *   voxels[r * max_voxels + s]  s-th visited voxel: xyz = i, j, k; w = the axis crossed to enter it
 *                               (0, 1, 2), -1 for the first voxel
 *   t_enter[r * max_voxels + s] the ray parameter where it was entered (GvRay.t)
 *   occupied[r * max_voxels + s] 1 when the voxel is occupied
 *   result[r]                   x = voxels visited (0: the ray misses the grid), y = 1 when the walk
 *                               ended by leaving the grid, 0 when it hit max_voxels
 *   shape: one work item per ray, n rays. */
#ifndef WG_SIZE
#define WG_SIZE 64
#endif

#include "grid_view.h"

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void grid_view_fetch(
    VOXR_GRID_VIEW_PARAMS, __global const int4* query, uint n, __global uint* flags,
    __global uint* rank, __global uint* count, __global uint* material, __global float* normal) {
  const uint q = get_global_id(0);
  if (q >= n) return;
  const GridView g = VOXR_GRID_VIEW();
  const int4 v = query[q];
  uint f = 0, r = ~0u, c = 0, m = 0;
  float3 nrm = (float3)(0.0f);
  if (gv_contains(&g, v.x, v.y, v.z)) {
    const ulong linear = gv_linear(&g, v.x, v.y, v.z);
    const int occ = gv_occupied(&g, linear);
    f = (uint)occ | ((uint)gv_inside(&g, linear) << 1);
    if (occ) {
      /* Without a rank index gv_rank must not be called; the channel accessors then see rank 0 and, the
       * sparse channels being absent, return 0 without reading. */
      const uint at = gv_has_rank(&g) ? gv_rank(&g, linear) : 0u;
      if (gv_has_rank(&g)) r = at;
      c = gv_count(&g, at);
      m = gv_material(&g, at);
      nrm = gv_normal(&g, at);
    }
  }
  flags[q] = f;
  rank[q] = r;
  count[q] = c;
  material[q] = m;
  vstore3(nrm, q, normal);
}

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void grid_view_march(
    VOXR_GRID_VIEW_PARAMS, __global const float4* rays, uint n, uint max_voxels, __global int4* voxels,
    __global float* t_enter, __global uint* occupied, __global uint2* result) {
  const uint ray = get_global_id(0);
  if (ray >= n) return;
  const GridView g = VOXR_GRID_VIEW();
  const float3 origin = rays[2 * (ulong)ray].xyz, dir = rays[2 * (ulong)ray + 1].xyz;
  const ulong base = (ulong)ray * max_voxels;
  GvRay r;
  uint visited = 0, left = 0;
  if (gv_ray_begin(&r, &g, origin, dir)) {
    int axis = -1;
    while (visited < max_voxels) {
      voxels[base + visited] = (int4)(r.i, r.j, r.k, axis);
      t_enter[base + visited] = r.t;
      occupied[base + visited] = (uint)gv_occupied(&g, gv_linear(&g, r.i, r.j, r.k));
      ++visited;
      axis = gv_ray_step(&r, &g);
      if (axis < 0) {
        left = 1;
        break;
      }
    }
  } else {
    left = 1;
  }
  result[ray] = (uint2)(visited, left);
}
