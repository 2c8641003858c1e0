/* refraction_path.h — what every refraction kernel (refract_voxel.cl, image_space.cl, distance_maps.cl)
 * shares: the camera ray of a pixel, the identity path of a pixel that sees no dielectric, which pixels see
 * one and the list of them a refraction kernel runs over, Snell refraction of a vector, the exact front
 * surface, an end without a surface, and the crossing of a dielectric interface (rp_interface: the media
 * stack of media_stack.h). OpenCL only; the interface optics themselves are in refraction.h. */
#ifndef VOXR_REFRACTION_PATH_H
#define VOXR_REFRACTION_PATH_H

#include "media_stack.h"
#include "refraction.h"
#include "voxr_layout.h"

/* The unit direction of pixel (x, y)'s ray through its centre (CameraFrame::ray_direction). */
inline float3 rp_camera_direction(const RenderCamera* cam, uint x, uint y) {
  const float3 forward = (float3)(cam->forward[0], cam->forward[1], cam->forward[2]);
  const float3 right = (float3)(cam->right[0], cam->right[1], cam->right[2]);
  const float3 up = (float3)(cam->up[0], cam->up[1], cam->up[2]);
  const float sx = (2.0f * ((float)x + 0.5f) / (float)cam->width - 1.0f) * cam->tan_half_fov_y * cam->aspect;
  const float sy = (1.0f - 2.0f * ((float)y + 0.5f) / (float)cam->height) * cam->tan_half_fov_y;
  return normalize(forward + sx * right + sy * up);
}

inline void rp_store3(float* out, float3 v) {
  out[0] = v.x;
  out[1] = v.y;
  out[2] = v.z;
}

/* The path of a pixel whose camera ray (direction dir) meets no dielectric. */
inline RefractionPath rp_identity(float3 dir) {
  RefractionPath p;
  rp_store3(p.throughput, (float3)(1.0f));
  p.events = 0u;
  rp_store3(p.reflect_direction, (float3)(0.0f));
  p.fresnel = 0.0f;
  rp_store3(p.exit_position, (float3)(0.0f));
  p.pad0 = 0.0f;
  rp_store3(p.exit_direction, dir);
  p.pad1 = 0.0f;
  return p;
}

/* Mirror d (unit) about n (unit). */
inline float3 rp_reflect(float3 d, float3 n) {
  return d - 2.0f * dot(d, n) * n;
}

/* Refracts unit d at a surface of unit normal n (either orientation) from index n1 into n2. Returns 1 and
 * the refracted unit direction in *t, or 0 on total internal reflection (*t is then the mirror direction).
 * *cos_i receives the incidence cosine (>= 0). */
inline int rp_refract(float3 d, float3 n, float n1, float n2, float3* t, float* cos_i) {
  if (dot(d, n) > 0.0f) n = -n; /* n faces the incoming ray */
  const float ci = fmin(-dot(d, n), 1.0f);
  *cos_i = ci;
  const float ct = voxr_refracted_cos(ci, n1, n2);
  if (ct < 0.0f) {
    *t = rp_reflect(d, n);
    return 0;
  }
  const float eta = n1 / n2;
  *t = normalize(eta * d + (eta * ci - ct) * n);
  return 1;
}

/* The end of a path that meets no surface: VOXR_NO_TRIANGLE and zeros. */
inline SurfaceSample rp_no_surface(void) {
  SurfaceSample s;
  rp_store3(s.position, (float3)(0.0f));
  s.triangle = VOXR_NO_TRIANGLE;
  rp_store3(s.normal, (float3)(0.0f));
  s.material = 0u;
  rp_store3(s.geometric_normal, (float3)(0.0f));
  s.distance = 0.0f;
  s.barycentric[0] = s.barycentric[1] = 0.0f;
  s.pad[0] = s.pad[1] = 0.0f;
  return s;
}

/* Whether primary sample s is a dielectric surface: the pixels a refraction method traces
 * (dielectric_pixels.cl lists them; shade.cl reads their paths). */
inline int rp_sees_dielectric(SurfaceSample s, __global const RenderMaterial* materials,
                              uint material_count) {
  return s.triangle != VOXR_NO_TRIANGLE &&
         materials[min(s.material, material_count - 1u)].kind == VOXR_MATERIAL_DIELECTRIC;
}

/* The pixel of work item `slot` of a refraction kernel run over the list of pixels that see a dielectric
 * (dielectric_pixels.cl): 1 and the pixel's index in *id, or 0 past the list's device-side count. */
inline int rp_listed_pixel(__global const uint* pixel_list, __global const uint* pixel_count, uint slot,
                           uint* id) {
  if (slot >= *pixel_count) return 0;
  *id = pixel_list[slot];
  return 1;
}

/* Every refraction kernel's start at a listed pixel, whose camera ray (direction dir) sees primary sample s,
 * a dielectric: the front surface, exact. *path receives the identity path with Schlick's F and the mirror
 * direction (the environment it reflects), *t the refracted direction (n1 = 1 < n2: never total internal
 * reflection), *cos_i the incidence cosine. */
inline void rp_front_surface(SurfaceSample s, float3 dir, __global const RenderMaterial* materials,
                             uint material_count, RefractionPath* path, float3* t, float* cos_i) {
  const uint m0 = min(s.material, material_count - 1u);
  *path = rp_identity(dir);
  const float3 n_front = vload3(0, s.normal); /* turned towards the eye: outward here */
  const float ior = materials[m0].ior;
  rp_refract(dir, n_front, 1.0f, ior, t, cos_i);
  path->fresnel = voxr_schlick(*cos_i, 1.0f, ior);
  rp_store3(path->reflect_direction, rp_reflect(dir, n_front));
}

/* The index of refraction of medium `medium` (a material id, or VOXR_MEDIA_AIR: 1). */
inline float rp_medium_ior(uint medium, __global const RenderMaterial* materials) {
  return medium == VOXR_MEDIA_AIR ? 1.0f : materials[medium].ior;
}

/* The media stack of a path that has refracted into its first dielectric, material m0, at the front
 * surface (rp_front_surface: the camera is outside every medium). */
inline VoxrMedia rp_media_front(uint m0) {
  VoxrMedia media = voxr_media_empty();
  voxr_media_cross(&media, m0, 1);
  return media;
}

/* A path along unit *dir inside `media` meets a dielectric interface of material `mat`, unit normal n
 * (either orientation), whose winding normal (outward) makes `facing` = dot(dir, outward) with the ray:
 * entered or left by media_stack.h's rule; refracts by Snell's law (Schlick 1 - F into *throughput, the
 * media stack crossed) or mirrors on total internal reflection (VOXR_PATH_TIR), and counts the event; the
 * new direction goes to *new_dir. Between equal indices (a solid nested in another of the same material)
 * there is no interface: the ray goes straight on, F = 0, no event is counted, only the stack changes.
 * Returns 0, having changed nothing but VOXR_PATH_LOST in *events, when `mat` would need a new entry with the
 * stack full (VOXR_MAX_MEDIA): nested deeper than it holds, the path ends rather than guess. The caller
 * checks the event limit. The one interface rule of every refraction kernel and the reference. */
inline int rp_interface(float3 dir, float3 n, float facing, uint mat, VoxrMedia* media,
                        __global const RenderMaterial* materials, float3* throughput, uint* events,
                        float3* new_dir) {
  const int enters = voxr_media_enters(media, mat, facing);
  if (voxr_media_overflows(media, mat, enters)) {
    *events |= VOXR_PATH_LOST;
    return 0;
  }
  const float n1 = rp_medium_ior(voxr_media_top(media), materials);
  const float n2 = rp_medium_ior(voxr_media_far(media, mat, enters), materials);
  float cos_i;
  if (n1 == n2) { /* index-matched: no interface (no event), straight on */
    *new_dir = dir;
    voxr_media_cross(media, mat, enters);
    return 1;
  }
  if (rp_refract(dir, n, n1, n2, new_dir, &cos_i)) {
    *throughput *= 1.0f - voxr_schlick(cos_i, n1, n2);
    voxr_media_cross(media, mat, enters);
  } else {
    *events |= VOXR_PATH_TIR;
  }
  ++*events;
  return 1;
}

#endif
