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
