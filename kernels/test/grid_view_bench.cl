/* grid_view_bench.cl — a consumer of the normal channel, written twice so bench/grid_view_bench.cpp can
 * measure where per-voxel normals should live: sparse by rank (the DeviceVoxelGrid layout, one rank lookup
 * per read) or dense (one float3 per voxel of the grid, addressed by the linear index).
 *
 * gv_bench_scatter_normals: dense[3 * linear .. + 2] = the sparse normal of every set voxel; dense must be
 *   zero beforehand. in: the grid (rank index and normal channel). shape: one work item per occupancy word,
 *   `words` of them.
 * gv_bench_march_sparse / gv_bench_march_dense: per ray (rays[2r] = origin, rays[2r+1] = direction, xyz in
 *   grid units) walk the whole grid voxel by voxel (grid_view.h DDA) and read the normal of every occupied
 *   voxel met, through gv_rank + gv_normal or from `dense`. out: shade[r] = sum of |dot(normal, dir)| over
 *   those voxels, hits[r] = their number (identical for the two kernels). shape: one work item per ray.
 * gv_bench_march_occupancy: the same walk reading no normal, the baseline that the two normal reads are
 *   measured against; shade[r] = the number of voxels the ray visited. */
#ifndef WG_SIZE
#define WG_SIZE 64
#endif

#include "grid_view.h"

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void gv_bench_scatter_normals(
    VOXR_GRID_VIEW_PARAMS, ulong words, __global float* dense) {
  const ulong w = get_global_id(0);
  if (w >= words) return;
  const GridView g = VOXR_GRID_VIEW();
  const ulong ranked = g.ranked[w];
  uint bits = VOXR_RANKED_BITS(ranked), rank = VOXR_RANKED_RANK(ranked);
  while (bits != 0u) {
    const uint b = 31u - clz(bits & (0u - bits)); /* lowest set bit; OpenCL 1.2 has no ctz */
    vstore3(gv_normal(&g, rank), w * 32 + b, dense);
    ++rank;
    bits &= bits - 1u;
  }
}

#define NORMALS_SPARSE 0
#define NORMALS_DENSE 1
#define NORMALS_NONE 2

/* The shared walk; `source` is a literal in each kernel, so the compiler keeps one path per kernel. */
inline void march_normals(const GridView* g, __global const float* dense, int source,
                          __global const float4* rays, __global float* shade, __global uint* hits) {
  const uint ray = get_global_id(0);
  const float3 origin = rays[2 * (ulong)ray].xyz, dir = rays[2 * (ulong)ray + 1].xyz;
  float sum = 0.0f;
  uint n = 0, visited = 0;
  GvRay r;
  if (gv_ray_begin(&r, g, origin, dir)) {
    do {
      ++visited;
      const ulong linear = gv_linear(g, r.i, r.j, r.k);
      if (gv_occupied(g, linear)) {
        const float3 normal = source == NORMALS_DENSE    ? vload3(linear, dense)
                              : source == NORMALS_SPARSE ? gv_normal(g, gv_rank(g, linear))
                                                         : (float3)(0.0f);
        sum += fabs(dot(normal, dir));
        ++n;
      }
    } while (gv_ray_step(&r, g) >= 0);
  }
  shade[ray] = source == NORMALS_NONE ? (float)visited : sum;
  hits[ray] = n;
}

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void gv_bench_march_sparse(
    VOXR_GRID_VIEW_PARAMS, __global const float4* rays, uint n, __global float* shade, __global uint* hits) {
  if (get_global_id(0) >= n) return;
  const GridView g = VOXR_GRID_VIEW();
  march_normals(&g, g.normal, NORMALS_SPARSE, rays, shade, hits);
}

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void gv_bench_march_dense(
    VOXR_GRID_VIEW_PARAMS, __global const float* dense, __global const float4* rays, uint n,
    __global float* shade, __global uint* hits) {
  if (get_global_id(0) >= n) return;
  const GridView g = VOXR_GRID_VIEW();
  march_normals(&g, dense, NORMALS_DENSE, rays, shade, hits);
}

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void gv_bench_march_occupancy(
    VOXR_GRID_VIEW_PARAMS, __global const float4* rays, uint n, __global float* shade, __global uint* hits) {
  if (get_global_id(0) >= n) return;
  const GridView g = VOXR_GRID_VIEW();
  march_normals(&g, g.normal, NORMALS_NONE, rays, shade, hits);
}
