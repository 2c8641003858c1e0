/* shade.cl — one pixel's colour from what the camera sees there (SurfaceSample) and the transmittance the
 * shadow method found towards the light, by the one shading model (shading.h). */
#include "shading.h"
#include "voxr_layout.h"

#ifndef SHADE_GROUP
#define SHADE_GROUP 64
#endif

__kernel __attribute__((reqd_work_group_size(SHADE_GROUP, 1, 1))) void shade(
    __global const SurfaceSample* samples, __global const float4* transmittance, uint count,
    __global const RenderMaterial* materials, uint material_count, RenderLight light,
    __global float4* image) {
  const uint id = get_global_id(0);
  if (id >= count) return;
  const SurfaceSample s = samples[id];
  const float3 ambient = vload3(0, light.ambient);
  float3 c = ambient;
  if (s.triangle != VOXR_NO_TRIANGLE) {
    const RenderMaterial m = materials[min(s.material, material_count - 1u)];
    if (m.kind == VOXR_MATERIAL_DIELECTRIC) {
      c = (float3)(voxr_shade_dielectric_flat(ambient.x, m.absorption[0]),
                   voxr_shade_dielectric_flat(ambient.y, m.absorption[1]),
                   voxr_shade_dielectric_flat(ambient.z, m.absorption[2]));
    } else {
      const float3 p = vload3(0, s.position);
      float3 to_light, irradiance = vload3(0, light.intensity);
      if (light.directional) {
        to_light = -vload3(0, light.direction);
      } else {
        const float3 d = vload3(0, light.position) - p;
        const float dist2 = dot(d, d);
        to_light = d * rsqrt(dist2);
        irradiance /= dist2;
      }
      const float cos_theta = dot(vload3(0, s.normal), to_light);
      const float3 t = transmittance[id].xyz;
      c = (float3)(voxr_shade_surface(m.color[0], ambient.x, irradiance.x, cos_theta, t.x),
                   voxr_shade_surface(m.color[1], ambient.y, irradiance.y, cos_theta, t.y),
                   voxr_shade_surface(m.color[2], ambient.z, irradiance.z, cos_theta, t.z));
    }
  }
  image[id] = (float4)(c, 1.0f);
}
