/* layout_probe.cl — writes the device compiler's sizes and offsets of the shared layout structs so a test
 * can compare them with the host's (tests/layout_test.cpp).
 * out: sizes[0..7]  shape: a single work item. */
#include "voxr_layout.h"

#define VOX_OFFSET(var, field) ((uint)((__private char*)&(var).field - (__private char*)&(var)))

__kernel void layout_probe(__global uint* sizes) {
  VoxGridParams p;
  VoxCopy c;
  sizes[0] = sizeof(VoxGridParams);
  sizes[1] = VOX_OFFSET(p, world_to_grid);
  sizes[2] = VOX_OFFSET(p, dims);
  sizes[3] = VOX_OFFSET(p, rows_per_copy);
  sizes[4] = VOX_OFFSET(p, triangle_count);
  sizes[5] = sizeof(VoxCopy);
  sizes[6] = VOX_OFFSET(c, slice_block);
  sizes[7] = VOXR_SUBVOXEL;
}
