/* triangle_bricks.cl — the empty-space grid of the triangle lists' march (host/render/triangle_grid.h,
 * kernels/common/triangle_grid.h): one bit per VOXR_BRICK^3 voxels, set when a voxel of the brick is
 * occupied, so a ray crosses an empty brick in one step. The voxel refraction march (refract_voxel.cl) reads
 * grids built by this kernel too, one per level.
 * in: the occupancy bits; out: bricks (cleared before); shape: one work item per 32-bit occupancy word. */
#include "voxr_layout.h"

#ifndef WG_SIZE
#define WG_SIZE 64
#endif

/* Brick (bi, bj, bk)'s bit is ((bk * brick_dims.y + bj) * brick_dims.x + bi). */
__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void triangle_bricks(__global const uint* occ,
                                                                                   ulong words, uint4 dims,
                                                                                   uint4 brick_dims,
                                                                                   __global uint* bricks) {
  const ulong w = get_global_id(0);
  if (w >= words) return;
  uint bits = occ[w];
  while (bits != 0u) {
    const uint b = 31u - clz(bits);
    bits &= ~(1u << b);
    const ulong v = w * 32ul + b;
    const ulong row = v / dims.x;
    const uint i = (uint)(v - row * dims.x), j = (uint)(row % dims.y), k = (uint)(row / dims.y);
    if (k >= dims.z) continue;
    const ulong brick =
        ((ulong)(k / VOXR_BRICK) * brick_dims.y + j / VOXR_BRICK) * brick_dims.x + i / VOXR_BRICK;
    atomic_or(&bricks[brick >> 5], 1u << (uint)(brick & 31));
  }
}
