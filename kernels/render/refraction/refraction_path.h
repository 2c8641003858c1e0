/* refraction_path.h — what every refraction kernel (refract_voxel.cl, image_space.cl, distance_maps.cl)
 * shares: the camera ray of a pixel, the identity path of a pixel that sees no dielectric, which pixels see
 * one and the list of them a refraction kernel runs over, Snell refraction of a vector, the exact front
 * surface, and an end without a surface. OpenCL only; the interface optics themselves are in
 * refraction.h. */
#ifndef VOXR_REFRACTION_PATH_H
#define VOXR_REFRACTION_PATH_H

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

/* The parity media stack (refraction.h) at a surface of material `mat`, for a path inside media[0..depth-1]
 * (innermost last): the index of `mat` in the stack (the surface is left), or -1 (it is entered). */
inline int rp_medium_index(const uint* media, uint depth, uint mat) {
  int inside = -1;
  for (uint k = 0; k < depth; ++k)
    if (media[k] == mat) inside = (int)k;
  return inside;
}

/* The indices of refraction on both sides of that surface: n1 the innermost medium's (air: 1); n2 that of
 * `mat` when entering it, of the medium below when leaving the innermost (air at the bottom), n1 when leaving
 * an outer one (overlapping solids keep the ray in the innermost; the reference does the same: next_ior). */
inline void rp_interface_iors(const uint* media, uint depth, int inside, uint mat,
                              __global const RenderMaterial* materials, float* n1, float* n2) {
  *n1 = depth > 0u ? materials[media[depth - 1u]].ior : 1.0f;
  *n2 = inside < 0                   ? materials[mat].ior
        : (uint)inside + 1u == depth ? (inside > 0 ? materials[media[inside - 1]].ior : 1.0f)
                                     : *n1;
}

/* After refracting through that surface: media[inside] is left, or `mat` entered (the caller has checked
 * that the stack has room). */
inline void rp_cross_medium(uint* media, uint* depth, int inside, uint mat) {
  if (inside >= 0) {
    for (uint k = (uint)inside; k + 1u < *depth; ++k) media[k] = media[k + 1u];
    --*depth;
  } else {
    media[(*depth)++] = mat;
  }
}

/* A path along unit *dir inside media[0..*depth) meets a dielectric interface of material `mat`, unit normal
 * n (either orientation): refracts by Snell's law (Schlick 1 - F into *throughput, the media stack crossed)
 * or mirrors on total internal reflection (VOXR_PATH_TIR), and counts the event; the new direction goes to
 * *new_dir. Returns 0, having changed nothing but VOXR_PATH_LOST in *events, when `mat` would be entered
 * with the stack full (max_media): nested deeper than it holds, the path ends rather than guess. The
 * caller checks the event limit. The one interface rule of every refraction kernel and the reference. */
inline int rp_interface(float3 dir, float3 n, uint mat, uint* media, uint* depth, uint max_media,
                        __global const RenderMaterial* materials, float3* throughput, uint* events,
                        float3* new_dir) {
  const int inside = rp_medium_index(media, *depth, mat);
  if (inside < 0 && *depth == max_media) {
    *events |= VOXR_PATH_LOST;
    return 0;
  }
  float n1, n2, cos_i;
  rp_interface_iors(media, *depth, inside, mat, materials, &n1, &n2);
  if (rp_refract(dir, n, n1, n2, new_dir, &cos_i)) {
    *throughput *= 1.0f - voxr_schlick(cos_i, n1, n2);
    rp_cross_medium(media, depth, inside, mat);
  } else {
    *events |= VOXR_PATH_TIR;
  }
  ++*events;
  return 1;
}

#endif
