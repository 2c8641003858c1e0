/* shadow_lookup.cl — each receiver's transmittance from a light-grid transmittance volume
 * (shadow_transmittance.cl): the receiver, pushed off its surface by `normal_offset` columns along the normal
 * turned to the light, is interpolated bilinearly between the four nearest columns, each read linearly
 * within its slab at its own depth: where the receiver's plane crosses that column, moved `bias` slabs
 * (and, conservative grids, `slope_bias` x the plane's depth span over a column) towards the light
 * (sf_column_depth: a plane never shadows itself, however grazing the light). Uniform with opaque and
 * transparent casters also tests each column against a depth map of the opaque casters, which block.
 * Receivers outside the grid's columns are lit: the grid covers every caster that can shadow a receiver
 * (host/render/light_frame.h). */
#include "shadow_frame.h"

#ifndef SHADOW_GROUP
#define SHADOW_GROUP 64
#endif

/* The packed transmittance at the far face of slab k of column c (shadow_transmittance.cl). */
inline uint slab_value(__global const uint* volume, __global const uint2* tails, ulong c, uint dz, uint k) {
  const uint2 tail = tails[c];
  return k < tail.x ? volume[c * dz + k] : tail.y;
}

/* Transmittance of column `c` at depth z (grid units). */
inline float3 column_at(__global const uint* volume, __global const uint2* tails, ulong c, uint dz, float z) {
  if (z <= 0.0f) return (float3)(1.0f);
  const float kf = floor(z);
  if (kf >= (float)dz) return sf_unpack(tails[c].y);
  const uint k = (uint)kf;
  const float3 before = k > 0 ? sf_unpack(slab_value(volume, tails, c, dz, k - 1)) : (float3)(1.0f);
  return mix(before, sf_unpack(slab_value(volume, tails, c, dz, k)), z - kf);
}

/* What column (i, j) lets through to a receiver at grid point g with plane slope `slope`: the volume at the
 * plane's depth there (sf_column_depth) and, with `opaque_depth` (uniform where opaque and transparent
 * casters mix), the opaque casters' depth map there (texel (i, dims.y - 1 - j)). */
inline float3 column_tap(const ShadowFrame* f, __global const uint* volume, __global const uint2* tails,
                         __global const ulong* opaque_depth, uint has_opaque_depth, float3 g, float2 slope,
                         int i, int j, float bias, float slope_bias) {
  const uint dx = f->dims[0], dy = f->dims[1], dz = f->dims[2];
  const float z = sf_column_depth(f, g, slope, i, j, bias, slope_bias);
  float3 t = column_at(volume, tails, (ulong)j * dx + (ulong)i, dz, z);
  if (has_opaque_depth)
    t *= sf_depth_lit(opaque_depth, (ulong)(dy - 1u - (uint)j) * dx + (ulong)i, z / (float)dz);
  return t;
}

__kernel __attribute__((reqd_work_group_size(SHADOW_GROUP, 1, 1))) void shadow_lookup(
    __global const SurfaceSample* samples, uint count, __global const RenderMaterial* materials,
    uint material_count, RenderLight light, ShadowFrame frame, __global const uint* volume,
    __global const uint2* tails, __global const ulong* opaque_depth, uint has_opaque_depth, float bias,
    float slope_bias, float normal_offset, __global float4* transmittance) {
  const uint id = get_global_id(0);
  if (id >= count) return;
  const SurfaceSample s = samples[id];
  float3 t = (float3)(1.0f);
  float3 gp;
  float2 slope;
  if (sf_receiver(&frame, &light, &s, materials, material_count, normal_offset, &gp, &slope)) {
    const uint dx = frame.dims[0], dy = frame.dims[1];
    const float x = gp.x - 0.5f, y = gp.y - 0.5f;
    const float fx = floor(x), fy = floor(y);
    const float wx = x - fx, wy = y - fy;
    const int i0 = clamp((int)fx, 0, (int)dx - 1), i1 = clamp((int)fx + 1, 0, (int)dx - 1);
    const int j0 = clamp((int)fy, 0, (int)dy - 1), j1 = clamp((int)fy + 1, 0, (int)dy - 1);
    const float3 a = column_tap(&frame, volume, tails, opaque_depth, has_opaque_depth, gp, slope, i0, j0,
                                bias, slope_bias),
                 b = column_tap(&frame, volume, tails, opaque_depth, has_opaque_depth, gp, slope, i1, j0,
                                bias, slope_bias);
    const float3 c = column_tap(&frame, volume, tails, opaque_depth, has_opaque_depth, gp, slope, i0, j1,
                                bias, slope_bias),
                 d = column_tap(&frame, volume, tails, opaque_depth, has_opaque_depth, gp, slope, i1, j1,
                                bias, slope_bias);
    t = mix(mix(a, b, wx), mix(c, d, wx), wy);
  }
  transmittance[id] = (float4)(t, 1.0f);
}
