/* shadow_frame.h — a light's grid as the shadow kernels read it (voxr_layout.h ShadowFrame,
 * host/render/light_frame.h), and the transmittance volume's packing. */
#ifndef SHADOW_FRAME_H
#define SHADOW_FRAME_H

#include "voxr_layout.h"

/* Anchor-relative world point -> light grid units (LightFrame::to_grid on the host). */
inline float3 sf_to_grid(const ShadowFrame* f, float3 p) {
  const float* m = f->to_light;
  const float3 q = (float3)(((m[0] * p.x + m[1] * p.y) + m[2] * p.z) + m[3],
                            ((m[4] * p.x + m[5] * p.y) + m[6] * p.z) + m[7],
                            ((m[8] * p.x + m[9] * p.y) + m[10] * p.z) + m[11]);
  if (!f->projective) return q;
  return (float3)((q.x / q.z - f->u0) * f->inv_du, (q.y / q.z - f->v0) * f->inv_dv,
                  (f->inv_near - 1.0f / q.z) * f->depth_scale);
}

/* World length of column (i, j)'s centre ray inside slab k (LightFrame::slab_length). */
inline float sf_slab_length(const ShadowFrame* f, uint i, uint j, uint k) {
  if (!f->projective) return f->voxel_size;
  const float u = f->u0 + ((float)i + 0.5f) / f->inv_du;
  const float v = f->v0 + ((float)j + 0.5f) / f->inv_dv;
  const float z0 = 1.0f / (f->inv_near - (float)k / f->depth_scale);
  const float z1 = 1.0f / (f->inv_near - (float)(k + 1) / f->depth_scale);
  return (z1 - z0) * sqrt(1.0f + u * u + v * v);
}

/* World size of one column at point p's depth: the lateral footprint a normal offset is measured in. */
inline float sf_column_width(const ShadowFrame* f, float3 p) {
  if (!f->projective) return f->voxel_size;
  const float* m = f->to_light;
  const float z = ((m[8] * p.x + m[9] * p.y) + m[10] * p.z) + m[11];
  return z / f->inv_du;
}

/* Where receiver `s` looks its transmittance up, in grid units (both shadow lookups): pushed off its surface
 * by normal_offset columns along the geometric normal turned to the light. Returns 0 when the sample is no
 * receiver (no triangle, or a dielectric: shaded flat) or lies outside the grid's columns, where no caster
 * can reach it (host/render/light_frame.h): lit either way. */
inline int sf_receiver(const ShadowFrame* f, const RenderLight* light, const SurfaceSample* s,
                       __global const RenderMaterial* materials, uint material_count, float normal_offset,
                       float3* grid) {
  if (s->triangle == VOXR_NO_TRIANGLE ||
      materials[min(s->material, material_count - 1u)].kind == VOXR_MATERIAL_DIELECTRIC)
    return 0;
  float3 p = vload3(0, s->position);
  float3 n = vload3(0, s->geometric_normal);
  const float3 to_light =
      light->directional ? -vload3(0, light->direction) : normalize(vload3(0, light->position) - p);
  if (dot(n, to_light) < 0.0f) n = -n;
  p += n * (normal_offset * sf_column_width(f, p));
  *grid = sf_to_grid(f, p);
  return grid->x >= 0.0f && grid->y >= 0.0f && grid->x <= (float)f->dims[0] && grid->y <= (float)f->dims[1];
}

/* Transmittance volume: one word per voxel, column-major (k fastest: a column is contiguous), RGB in 10 bits
 * each, the transmittance from the light to the far face of the voxel's slab. */
inline uint sf_pack(float3 t) {
  const uint3 q = convert_uint3_rte(clamp(t, 0.0f, 1.0f) * 1023.0f);
  return q.x | (q.y << 10) | (q.z << 20);
}
inline float3 sf_unpack(uint w) {
  return (float3)((float)(w & 1023u), (float)((w >> 10) & 1023u), (float)((w >> 20) & 1023u)) *
         (1.0f / 1023.0f);
}

#endif
