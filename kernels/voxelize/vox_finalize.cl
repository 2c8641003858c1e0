/* vox_finalize.cl — unpacks the attribute accumulators of the second raster pass (vox_scanline.h):
 * acc[2r] = sum(n.x) + count * 2^32, acc[2r+1] = sum(n.y) + sum(n.z) * 2^32 (each sum below 2^31 in
 * magnitude), into the count, the fixed-point normal sum and the unit normal (zero where the sum cancels,
 * e.g. a voxel touched by both sides of a thin sheet), and the colour sums (color_acc[2r] = R + G 2^32,
 * color_acc[2r+1] = B + A 2^32) into the mean RGBA8 colour (vox_color.h vox_color_mean). `channels`
 * (ChannelSet bits) selects the outputs.
 * entries: the length of the accumulators and outputs the host allocated; voxel_count: the set voxels (on
 * the device: either may be the smaller). shape: one work item per entry. */
#ifndef WG_SIZE
#define WG_SIZE 64
#endif
/* The channel bits VOX_CH_* come from the channel table (host/grid/channel_table.h). */
#ifndef VOX_CH_COUNT
#error "vox_finalize needs the channel defines of host/grid/channel_table.h"
#endif
#include "vox_color.h"

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void vox_finalize(
    __global const long* acc, __global uint* count, __global int* nsum, __global float* normal,
    uint entries, __global const ulong* voxel_count, uint channels, __global const long* color_acc,
    __global uint* color) {
  const uint r = get_global_id(0);
  if (r >= entries || r >= *voxel_count) return;
  const long p0 = acc[2 * (ulong)r];
  const int nx = as_int((uint)p0);
  const uint pairs = (uint)((p0 - nx) / (1L << 32));
  if (channels & VOX_CH_COUNT) count[r] = pairs;
  if (channels & VOX_CH_COLOR) color[r] = vox_color_mean(color_acc[2 * (ulong)r], color_acc[2 * (ulong)r + 1], pairs);
  if (!(channels & VOX_CH_NORMAL)) return;
  const long p1 = acc[2 * (ulong)r + 1];
  const int ny = as_int((uint)p1);
  const int nz = (int)((p1 - ny) / (1L << 32)); /* exact: the difference is a multiple */
  const ulong base = 3 * (ulong)r;
  nsum[base] = nx;
  nsum[base + 1] = ny;
  nsum[base + 2] = nz;
  const float3 s = (float3)((float)nx, (float)ny, (float)nz);
  const float len = length(s);
  const float3 n = len > 0.0f ? s / len : (float3)(0.0f);
  normal[base] = n.x;
  normal[base + 1] = n.y;
  normal[base + 2] = n.z;
}
