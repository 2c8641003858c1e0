/* shadow_filter.cl — the light-space shadow-map baselines (host/render/light_space_maps.h).
 *   shadow_filter_accumulate: per covered texel of a transparent caster (a raster record,
 *     raster_coverage.h), add its optical depth in fixed point with integer atomics (order-independent):
 *     sheet -ln(t) per crossing; dielectric -sigma_a d on faces towards the light and +sigma_a d on faces
 * away (d: distance from the light along the texel's ray), which sums to sigma_a x thickness.
 *   shadow_map_lookup: receivers against the depth map (visibility words, opaque casters or all casters)
 *     with 2x2 percentage-closer filtering, each texel compared at the receiver plane's depth in its column
 *     (sf_column_depth); the filter method multiplies by exp(-optical depth). */
#include "raster_coverage.h"
#include "shadow_frame.h"

#ifndef SHADOW_GROUP
#define SHADOW_GROUP 64
#endif

/* Optical depth units per 1 (fixed point of the filter map). */
#define FILTER_ONE 1024.0f

/* World distance from the light to depth z_ndc along texel (x, y)'s ray (up to a constant for
 * orthographic frames, which cancels between a dielectric's faces). */
inline float light_distance(const ShadowFrame* f, uint x, uint y, float z_ndc) {
  const float gz = z_ndc * (float)f->dims[2];
  if (!f->projective) return gz * f->voxel_size;
  const float u = f->u0 + ((float)x + 0.5f) / f->inv_du;
  const float v = f->v0 + ((float)(f->dims[1] - 1u - y) + 0.5f) / f->inv_dv;
  const float z = 1.0f / (f->inv_near - gz / f->depth_scale);
  return z * sqrt(1.0f + u * u + v * v);
}

__kernel __attribute__((reqd_work_group_size(SHADOW_GROUP, 1, 1))) void shadow_filter_accumulate(
    ShadowFrame frame, RenderLight light, __global const RasterPrim* prims,
    __global const CopyRecord* records, uint record_count, __global const float4* positions,
    __global const uint4* triangles, __global const RenderMaterial* materials, uint material_count,
    __global int* tau) {
  const uint gid = get_global_id(0);
  if (gid >= record_count) return;
  const CopyRecord rec = records[gid];
  __global const RasterPrim* prim = prims + rec.triangle;
  const uint width = frame.dims[0], height = frame.dims[1];
  const uint4 tri = triangles[rec.triangle];
  const RenderMaterial m = materials[min(tri.w, material_count - 1u)];
  /* A dielectric face the light sees from outside is entered, the others left (outward-wound closed meshes):
   * decided from the geometry, not from the image's winding, which depends on the light frame's handedness.
   */
  const float3 a = positions[tri.x].xyz, b = positions[tri.y].xyz, c = positions[tri.z].xyz;
  const float3 to_light = light.directional ? -vload3(0, light.direction) : vload3(0, light.position) - a;
  const float sign = dot(cross(b - a, c - a), to_light) > 0.0f ? -1.0f : 1.0f;
  ulong mask = raster_tile_mask(prim, rec.cell, width, height);
  uint x, y;
  while (raster_next_pixel(&mask, rec.cell, &x, &y)) {
    float3 add;
    if (m.kind == VOXR_MATERIAL_SHEET) {
      add = -log(max((float3)(m.transmittance[0], m.transmittance[1], m.transmittance[2]), (float3)(1e-30f)));
    } else {
      const float d = light_distance(&frame, x, y, raster_depth_at(prim, x, y, width, height));
      add = sign * d * (float3)(m.absorption[0], m.absorption[1], m.absorption[2]);
    }
    const int3 q = convert_int3_rte(clamp(add * FILTER_ONE, -1.0e9f, 1.0e9f));
    __global int* t = tau + 3 * ((ulong)y * width + x);
    atomic_add(t + 0, q.x);
    atomic_add(t + 1, q.y);
    atomic_add(t + 2, q.z);
  }
}

__kernel __attribute__((reqd_work_group_size(SHADOW_GROUP, 1, 1))) void shadow_map_lookup(
    __global const SurfaceSample* samples, uint count, __global const RenderMaterial* materials,
    uint material_count, RenderLight light, ShadowFrame frame, __global const ulong* depth,
    __global const int* tau, uint filter, float bias, float normal_offset, __global float4* transmittance) {
  const uint id = get_global_id(0);
  if (id >= count) return;
  const SurfaceSample s = samples[id];
  float3 result = (float3)(1.0f);
  float3 g;
  float2 slope;
  if (sf_receiver(&frame, &light, &s, materials, material_count, normal_offset, &g, &slope)) {
    const int w = (int)frame.dims[0], h = (int)frame.dims[1];
    /* Texel centres: column i at x = i + 0.5; image row y = dims.y - 1 - j. */
    const float x = g.x - 0.5f, y = g.y - 0.5f;
    const float fx = floor(x), fy = floor(y);
    const float wx = x - fx, wy = y - fy;
    float3 sum = (float3)(0.0f);
    for (int dj = 0; dj < 2; ++dj) {
      for (int di = 0; di < 2; ++di) {
        const int i = clamp((int)fx + di, 0, w - 1), j = clamp((int)fy + dj, 0, h - 1);
        const ulong texel = (ulong)(h - 1 - j) * (ulong)w + (ulong)i;
        const float receiver = sf_column_depth(&frame, g, slope, i, j, bias, 0.0f) / (float)frame.dims[2];
        float3 t = (float3)(sf_depth_lit(depth, texel, receiver));
        if (filter) {
          const int3 q = vload3(texel, tau);
          t *= exp(-max(convert_float3(q), 0.0f) / FILTER_ONE);
        }
        const float weight = (di ? wx : 1.0f - wx) * (dj ? wy : 1.0f - wy);
        sum += weight * t;
      }
    }
    result = sum;
  }
  transmittance[id] = (float4)(result, 1.0f);
}
