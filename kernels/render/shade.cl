/* shade.cl — one pixel's colour from where its refraction path ends (SurfaceSample), the transmittance the
 * shadow method found from there towards the light, and the path itself (RefractionPath):
 *   pixel = fresnel * environment(reflect_direction) + throughput * L(end)
 * L(end) by the one shading model (shading.h): the environment (environment.h) in the path's exit direction
 * where the end has no surface, a flat dielectric where refraction is off, a lit surface otherwise. The host
 * twin is render/shade_host.cpp shade_paths. */
#include "environment.h"
#include "shading.h"
#include "voxr_layout.h"

#ifndef SHADE_GROUP
#define SHADE_GROUP 64
#endif

__kernel __attribute__((reqd_work_group_size(SHADE_GROUP, 1, 1))) void shade(
    __global const SurfaceSample* ends, __global const float4* transmittance,
    __global const RefractionPath* paths, uint count, __global const RenderMaterial* materials,
    uint material_count, RenderLight light, __global const float* environment, uint environment_width,
    uint environment_height, __global float4* image) {
  const uint id = get_global_id(0);
  if (id >= count) return;
  const SurfaceSample s = ends[id];
  const RefractionPath path = paths[id];
  const float3 ambient = vload3(0, light.ambient);
  float3 c = (float3)(0.0f);
  if (s.triangle == VOXR_NO_TRIANGLE) {
    float rgb[3];
    voxr_environment_lookup(environment, environment_width, environment_height, path.exit_direction[0],
                            path.exit_direction[1], path.exit_direction[2], rgb);
    c = (float3)(rgb[0], rgb[1], rgb[2]);
  } else {
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
  c = (path.events & VOXR_PATH_LOST) ? (float3)(0.0f) : vload3(0, path.throughput) * c;
  if (path.fresnel > 0.0f) {
    float rgb[3];
    voxr_environment_lookup(environment, environment_width, environment_height, path.reflect_direction[0],
                            path.reflect_direction[1], path.reflect_direction[2], rgb);
    c += path.fresnel * (float3)(rgb[0], rgb[1], rgb[2]);
  }
  image[id] = (float4)(c, 1.0f);
}
