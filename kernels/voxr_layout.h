/* voxr_layout.h — the one description of everything the host and the kernels both read.
 * Written in the C subset that OpenCL C 1.2 and C++20 both accept: fixed-size scalar arrays, no vector
 * types, no padding surprises (every member is 4 bytes wide). The host static_asserts the sizes and a
 * test compares them with sizeof/offsetof measured by a kernel. */
#ifndef VOXR_LAYOUT_H
#define VOXR_LAYOUT_H

#ifndef __OPENCL_VERSION__
#include <stdint.h>
typedef uint32_t uint;
#endif

/* Vertices are snapped to a lattice of 1/VOXR_SUBVOXEL voxel in grid space, so every membership predicate
 * (triangle/box overlap, pixel-centre coverage, slab depth) is decided by exact 64-bit integer arithmetic:
 * identical on every device and equal to the CPU reference bit for bit. */
#define VOXR_SUBVOXEL_BITS 8
#define VOXR_SUBVOXEL (1 << VOXR_SUBVOXEL_BITS)

/* Triangles longer than this along any grid axis (in voxels) would overflow the exact predicates; the host
 * splits them before upload (host/voxelize/triangle_splitter.h). */
#define VOXR_MAX_TRIANGLE_EXTENT 2040

/* Normal sums are fixed point: each triangle adds its unit normal times VOXR_NORMAL_ONE. A voxel's sums are
 * packed into 32-bit halves (vox_scanline.h), which stay exact while at most VOXR_MAX_ATTRIBUTE_TRIANGLES
 * triangles write one voxel; the host refuses count/normal for meshes with more triangles than that. */
#define VOXR_NORMAL_ONE 256
#define VOXR_MAX_ATTRIBUTE_TRIANGLES ((1u << 23) - 1u)

/* Rasterization rules. */
#define VOXR_MODE_CONSERVATIVE 0 /* every voxel whose closed box the closed triangle touches */
#define VOXR_MODE_CENTER 1       /* voxel column centre inside the projection, depth in [k, k+1) */

/* Grid parameters passed by value to the voxelization kernels. */
typedef struct VoxGridParams {
  float world_to_grid[12]; /* rows of a 3x4 affine: world -> grid units */
  uint dims[4];            /* x, y, z, unused */
  uint rows_per_copy;      /* rows of one slab that a single raster work item handles */
  uint triangle_count;
  uint pad[2];
} VoxGridParams;

/* One duplicated triangle: the "geometry shader" output. The slice (slab k) and the block of rows inside
 * the triangle's row range are packed so a record is 8 bytes. */
typedef struct VoxCopy {
  uint triangle;
  uint slice_block; /* slice in the low 16 bits, row block in the high 16 */
} VoxCopy;

#define VOXR_COPY_SLICE(c) ((c).slice_block & 0xffffu)
#define VOXR_COPY_BLOCK(c) ((c).slice_block >> 16)
#define VOXR_MAX_BLOCKS 0xffffu

#endif
