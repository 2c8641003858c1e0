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

/* The receiver's plane (through p, normal n) in grid units, as the depth change per column: gz moves by
 * slope.x per column along x and slope.y along y. Both frames map planes to planes (the frustum's is
 * projective), so the plane's depth in another column is gz + slope . (column - receiver): the depth its
 * crossing has there, where a lookup must start (receiver plane depth, Isidoro 2006). Orthographic: the
 * normal in grid units is to_light's rotation of n; frustum: the plane n_v . q = d of the light's view is
 * 1/z = (n_v.x u + n_v.y v + n_v.z) / d, linear in u, v and 1/z, hence in grid units. A plane containing the
 * light's rays (edge-on) has no finite slope: infinities, which the lookups clamp. */
inline float2 sf_depth_slope(const ShadowFrame* f, float3 p, float3 n) {
  const float* m = f->to_light;
  const float3 nv =
      (float3)(((m[0] * n.x + m[1] * n.y) + m[2] * n.z), ((m[4] * n.x + m[5] * n.y) + m[6] * n.z),
               ((m[8] * n.x + m[9] * n.y) + m[10] * n.z));
  float3 a = nv;
  if (f->projective) {
    const float3 q = (float3)(((m[0] * p.x + m[1] * p.y) + m[2] * p.z) + m[3],
                              ((m[4] * p.x + m[5] * p.y) + m[6] * p.z) + m[7],
                              ((m[8] * p.x + m[9] * p.y) + m[10] * p.z) + m[11]);
    const float d = (nv.x * q.x + nv.y * q.y) + nv.z * q.z;
    a = (float3)(nv.x / f->inv_du, nv.y / f->inv_dv, d / f->depth_scale);
  }
  return (float2)(-a.x / a.z, -a.y / a.z);
}

/* The depth (grid units) at which a lookup reads column (i, j) for a receiver at grid point g whose plane has
 * `slope` (sf_depth_slope): the plane's depth at the column's centre ray, less `bias` slabs and, for a grid
 * whose voxelizer marks every voxel a surface touches (conservative), less `slope_bias` x the depth the plane
 * spans across one column (|slope.x| + |slope.y|), where such a grid marks its first voxel. The plane's depth
 * change is clamped to the grid's depth (an edge-on receiver). */
inline float sf_column_depth(const ShadowFrame* f, float3 g, float2 slope, int i, int j, float bias,
                             float slope_bias) {
  const float dz = (float)f->dims[2];
  float change = slope.x * (((float)i + 0.5f) - g.x) + slope.y * (((float)j + 0.5f) - g.y);
  change = isfinite(change) ? clamp(change, -dz, dz) : 0.0f;
  float span = slope_bias * (fabs(slope.x) + fabs(slope.y));
  span = isfinite(span) ? min(span, dz) : dz;
  return g.z + change - bias - span;
}

/* Where receiver `s` looks its transmittance up, in grid units (both shadow lookups): pushed off its surface
 * by normal_offset columns along the geometric normal turned to the light; `slope` is its plane's
 * (sf_depth_slope). Returns 0 when the sample is no receiver (no triangle, or a dielectric: shaded flat) or
 * lies outside the grid's columns, where no caster can reach it (host/render/light_frame.h): lit either way.
 */
inline int sf_receiver(const ShadowFrame* f, const RenderLight* light, const SurfaceSample* s,
                       __global const RenderMaterial* materials, uint material_count, float normal_offset,
                       float3* grid, float2* slope) {
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
  *slope = sf_depth_slope(f, p, n);
  return grid->x >= 0.0f && grid->y >= 0.0f && grid->x <= (float)f->dims[0] && grid->y <= (float)f->dims[1];
}

/* 1 where a receiver at depth `receiver` (grid depth / dims.z) sees the light past depth-map texel `texel`
 * (visibility words, host/render/light_space_maps.h: the nearest caster's depth in the high 32 bits, its
 * triangle in the low; VOXR_NO_TRIANGLE: no caster), else 0. */
inline float sf_depth_lit(__global const ulong* depth, ulong texel, float receiver) {
  const ulong word = depth[texel];
  const float occluder = (uint)(word & 0xffffffffu) == VOXR_NO_TRIANGLE ? 2.0f : as_float((uint)(word >> 32));
  return receiver <= occluder ? 1.0f : 0.0f;
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
