/* shade.cl — one pixel's colour from where its refraction path ends (SurfaceSample), the transmittance the
 * shadow method found from there towards the light, and the path itself (RefractionPath):
 *   pixel = fresnel * environment(reflect_direction) + throughput * L(end)
 * L(end) by the one shading model (shading.h): the environment (environment.h) in the path's exit direction
 * where the end has no surface, a flat dielectric where refraction is off, a lit surface otherwise. A pixel
 * whose primary sample is no dielectric has the identity path (refraction_path.h): its end is the primary
 * sample, its exit direction the camera ray's, and the kernels compute it rather than read it.
 *   shade:         with refraction: the end and path of a pixel that sees a dielectric are read from `ends`
 *                  and `paths` (written for those pixels only), every other pixel's are the identity.
 *   shade_primary: without refraction: every pixel's path is the identity.
 * One work item per pixel. The host twin is render/shade_host.cpp shade_paths. */
#include "environment.h"
#include "refraction_path.h"
#include "shading.h"

#ifndef SHADE_GROUP
#define SHADE_GROUP 64
#endif

/* The environment in unit direction d. */
inline float3 shade_environment(float3 d, __global const float* environment, uint environment_width,
                                uint environment_height) {
  float rgb[3];
  voxr_environment_lookup(environment, environment_width, environment_height, d.x, d.y, d.z, rgb);
  return (float3)(rgb[0], rgb[1], rgb[2]);
}

/* L(end) for end s of pixel id, a surface (s.triangle is not VOXR_NO_TRIANGLE). */
inline float3 shade_surface(SurfaceSample s, uint id, __global const float4* transmittance,
                            __global const RenderMaterial* materials, uint material_count,
                            RenderLight light) {
  const float3 ambient = vload3(0, light.ambient);
  const RenderMaterial m = materials[min(s.material, material_count - 1u)];
  if (m.kind == VOXR_MATERIAL_DIELECTRIC)
    return (float3)(voxr_shade_dielectric_flat(ambient.x, m.absorption[0]),
                    voxr_shade_dielectric_flat(ambient.y, m.absorption[1]),
                    voxr_shade_dielectric_flat(ambient.z, m.absorption[2]));
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
  return (float3)(voxr_shade_surface(m.color[0], ambient.x, irradiance.x, cos_theta, t.x),
                  voxr_shade_surface(m.color[1], ambient.y, irradiance.y, cos_theta, t.y),
                  voxr_shade_surface(m.color[2], ambient.z, irradiance.z, cos_theta, t.z));
}

/* The colour of pixel id under its identity path: L(primary sample), the environment in the camera ray's
 * direction where it has no surface. */
inline float3 shade_identity(SurfaceSample s, RenderCamera cam, uint id, __global const float4* transmittance,
                             __global const RenderMaterial* materials, uint material_count, RenderLight light,
                             __global const float* environment, uint environment_width,
                             uint environment_height) {
  if (s.triangle == VOXR_NO_TRIANGLE)
    return shade_environment(rp_camera_direction(&cam, id % cam.width, id / cam.width), environment,
                             environment_width, environment_height);
  return shade_surface(s, id, transmittance, materials, material_count, light);
}

__kernel __attribute__((reqd_work_group_size(SHADE_GROUP, 1, 1))) void shade(
    RenderCamera cam, __global const SurfaceSample* primary, __global const SurfaceSample* ends,
    __global const RefractionPath* paths, __global const float4* transmittance,
    __global const RenderMaterial* materials, uint material_count, RenderLight light,
    __global const float* environment, uint environment_width, uint environment_height,
    __global float4* image) {
  const uint id = get_global_id(0);
  if (id >= cam.width * cam.height) return;
  const SurfaceSample s0 = primary[id];
  if (!rp_sees_dielectric(s0, materials, material_count)) {
    image[id] = (float4)(shade_identity(s0, cam, id, transmittance, materials, material_count, light,
                                        environment, environment_width, environment_height),
                         1.0f);
    return;
  }
  const SurfaceSample s = ends[id];
  const RefractionPath path = paths[id];
  float3 c = s.triangle == VOXR_NO_TRIANGLE
                 ? shade_environment(vload3(0, path.exit_direction), environment, environment_width,
                                     environment_height)
                 : shade_surface(s, id, transmittance, materials, material_count, light);
  c = (path.events & VOXR_PATH_LOST) ? (float3)(0.0f) : vload3(0, path.throughput) * c;
  if (path.fresnel > 0.0f) {
    float rgb[3];
    voxr_environment_lookup(environment, environment_width, environment_height, path.reflect_direction[0],
                            path.reflect_direction[1], path.reflect_direction[2], rgb);
    c += path.fresnel * (float3)(rgb[0], rgb[1], rgb[2]);
  }
  image[id] = (float4)(c, 1.0f);
}

__kernel __attribute__((reqd_work_group_size(SHADE_GROUP, 1, 1))) void shade_primary(
    RenderCamera cam, __global const SurfaceSample* primary, __global const float4* transmittance,
    __global const RenderMaterial* materials, uint material_count, RenderLight light,
    __global const float* environment, uint environment_width, uint environment_height,
    __global float4* image) {
  const uint id = get_global_id(0);
  if (id >= cam.width * cam.height) return;
  const SurfaceSample s = primary[id];
  image[id] = (float4)(shade_identity(s, cam, id, transmittance, materials, material_count, light,
                                      environment, environment_width, environment_height),
                       1.0f);
}
