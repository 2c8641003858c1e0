/* image_space.cl — image-space refraction (host/render/image_space_refraction.h): Wyman 2005, "An Approximate
 * Image-Space Approach for Interactive Refraction", with nearby geometry (Wyman, GRAPHITE 2005). A pixel
 * whose primary sample is a dielectric refracts there (exact position, interpolated
 * normal), estimates the distance to the back surface from the back-face buffer's depth (d_V) and the
 * front hit's precomputed inward distance (d_N), reads the back-face buffer's normal where the estimated exit
 * point P2 projects, refracts out, and finds what the exit ray sees by the paper's iterative lookup in the
 * opaque surfaces' visibility buffer. The work items run over the list of those pixels
 * (dielectric_pixels.cl): only the listed pixels' ends and paths are written. The path model is
 * refraction.h's: Schlick F at the front surface, 1 - F per refraction, Beer-Lambert over d, total internal
 * reflection mirrors and costs nothing.
 *
 * The back-face samples were resolved with their normals turned towards the eye, which for a back face is
 * the inward normal; rp_refract orients the normal against the incoming ray itself, so either orientation
 * refracts alike. Fallbacks (documented in the header too): a pixel without a back-face sample, or whose
 * back face is not behind its front, takes d = d_N; a missing d_N (no per-vertex value) takes d = d_V (and a
 * pixel with neither passes straight through the front sample: d = 0); P2 projecting off the image or onto a
 * pixel without a back face reads the back face at the pixel itself; with no back face there either, the
 * ray leaves along T1 (no second bend, still one 1 - F for the exit).
 * in:  camera, primary/back/opaque samples (width * height each), materials, triangles (uint4) and the
 *      per-vertex inward distances of the mesh
 * out: ends[pixel] (SurfaceSample), paths[pixel] (RefractionPath) */
#include "refraction_path.h"

#ifndef PATH_GROUP
#define PATH_GROUP 64
#endif

/* The pixel (x, y) point p projects to, or 0 when it is behind the eye or off the image. */
inline int is_project(const RenderCamera* cam, float3 p, uint* x, uint* y) {
  const float3 eye = (float3)(cam->eye[0], cam->eye[1], cam->eye[2]);
  const float3 forward = (float3)(cam->forward[0], cam->forward[1], cam->forward[2]);
  const float3 right = (float3)(cam->right[0], cam->right[1], cam->right[2]);
  const float3 up = (float3)(cam->up[0], cam->up[1], cam->up[2]);
  const float3 v = p - eye;
  const float z = dot(v, forward);
  if (!(z > 0.0f)) return 0;
  /* sx = (2 px / width - 1) tan aspect, sy = (1 - 2 py / height) tan (rp_camera_direction). */
  const float sx = dot(v, right) / z, sy = dot(v, up) / z;
  const float px = (sx / (cam->tan_half_fov_y * cam->aspect) + 1.0f) * 0.5f * (float)cam->width;
  const float py = (1.0f - sy / cam->tan_half_fov_y) * 0.5f * (float)cam->height;
  if (!(px >= 0.0f && px < (float)cam->width && py >= 0.0f && py < (float)cam->height)) return 0;
  *x = min((uint)px, cam->width - 1u);
  *y = min((uint)py, cam->height - 1u);
  return 1;
}

/* d_N at the front sample: the per-vertex inward distances interpolated with its barycentrics; -1 when
 * unknown. */
inline float is_inward_distance(const SurfaceSample* s, __global const uint4* triangles,
                                __global const float* inward, const ImageSpaceParams* p) {
  if (s->triangle >= p->triangle_count) return -1.0f;
  const uint4 tri = triangles[s->triangle];
  if (tri.x >= p->inward_count || tri.y >= p->inward_count || tri.z >= p->inward_count) return -1.0f;
  const float u = s->barycentric[0], v = s->barycentric[1];
  const float d = (1.0f - u - v) * inward[tri.x] + u * inward[tri.y] + v * inward[tri.z];
  return isfinite(d) && d >= 0.0f ? d : -1.0f;
}

__kernel __attribute__((reqd_work_group_size(PATH_GROUP, 1, 1))) void image_space(
    RenderCamera cam, __global const SurfaceSample* primary, __global const uint* pixel_list,
    __global const uint* pixel_count, __global const SurfaceSample* back,
    __global const SurfaceSample* opaque, __global const RenderMaterial* materials, uint material_count,
    __global const uint4* triangles, __global const float* inward, ImageSpaceParams p,
    __global SurfaceSample* ends, __global RefractionPath* paths) {
  uint id;
  if (!rp_listed_pixel(pixel_list, pixel_count, get_global_id(0), &id)) return;
  const float3 dir = rp_camera_direction(&cam, id % cam.width, id / cam.width);
  const SurfaceSample s = primary[id];
  /* 1. The front surface, exact: Schlick's F reflects the environment, 1 - F refracts in. */
  RefractionPath path;
  float3 t1;
  float cos_i;
  rp_front_surface(s, dir, materials, material_count, &path, &t1, &cos_i);
  const uint m0 = min(s.material, material_count - 1u);
  const RenderMaterial glass = materials[m0];
  const float ior = glass.ior;
  float3 throughput = (float3)(1.0f - path.fresnel);
  uint events = 1u;

  /* 2. The distance to the back surface: d_V along the view ray, d_N along the inward normal, blended by
   * the ratio of the transmitted to the incident angle (its limit n1 / n2 at normal incidence). */
  const float3 p1 = vload3(0, s.position);
  const SurfaceSample b = back[id];
  const float d_v = b.triangle != VOXR_NO_TRIANGLE ? b.distance - s.distance : -1.0f;
  const float d_n = is_inward_distance(&s, triangles, inward, &p);
  const float theta_i = acos(clamp(cos_i, 0.0f, 1.0f));
  const float cos_t = voxr_refracted_cos(cos_i, 1.0f, ior);
  const float theta_t = acos(clamp(cos_t, 0.0f, 1.0f));
  const float ratio = theta_i > 1e-3f ? clamp(theta_t / theta_i, 0.0f, 1.0f) : 1.0f / ior;
  float d;
  if (d_v > 0.0f && d_n >= 0.0f)
    d = ratio * d_v + (1.0f - ratio) * d_n;
  else if (d_n >= 0.0f)
    d = d_n;
  else
    d = fmax(d_v, 0.0f);
  if (!isfinite(d)) d = 0.0f;
  const float3 p2 = p1 + d * t1;
  throughput *= exp(-vload3(0, glass.absorption) * d);

  /* 3. The back surface's normal where P2 projects (else at this pixel), and the refraction out. */
  uint x2, y2;
  SurfaceSample b2 = b;
  if (is_project(&cam, p2, &x2, &y2)) {
    const SurfaceSample candidate = back[y2 * cam.width + x2];
    if (candidate.triangle != VOXR_NO_TRIANGLE) b2 = candidate;
  }
  float3 t2 = t1;
  if (b2.triangle != VOXR_NO_TRIANGLE) {
    float cos_b;
    if (rp_refract(t1, vload3(0, b2.normal), ior, 1.0f, &t2, &cos_b))
      throughput *= 1.0f - voxr_schlick(cos_b, ior, 1.0f);
    else
      events |= VOXR_PATH_TIR;
  } else {
    throughput *= 1.0f - voxr_schlick(1.0f, ior, 1.0f);
  }
  ++events;

  /* 4. Nearby geometry: the iterative lookup along P2 + d_g T2 in the opaque buffer. */
  float d_g = p.scene_size;
  if (is_project(&cam, p2, &x2, &y2)) {
    const SurfaceSample o = opaque[y2 * cam.width + x2];
    if (o.triangle != VOXR_NO_TRIANGLE) d_g = length(vload3(0, o.position) - p2);
  }
  SurfaceSample end = rp_no_surface();
  int found = 0;
  for (uint k = 0; k < max(p.iterations, 1u); ++k) {
    uint xq, yq;
    if (!is_project(&cam, p2 + d_g * t2, &xq, &yq)) {
      found = 0;
      break;
    }
    end = opaque[yq * cam.width + xq];
    found = end.triangle != VOXR_NO_TRIANGLE;
    if (!found) break;
    d_g = length(vload3(0, end.position) - p2);
  }
  if (found) {
    /* The camera turned its normals towards the eye; the path meets the surface along t2. */
    const float3 ng = vload3(0, end.geometric_normal);
    if (dot(ng, t2) > 0.0f) {
      rp_store3(end.geometric_normal, -ng);
      rp_store3(end.normal, -vload3(0, end.normal));
    }
  } else {
    end = rp_no_surface();
    events |= VOXR_PATH_ENV;
  }

  rp_store3(path.throughput, throughput);
  path.events = events;
  rp_store3(path.exit_position, p2);
  rp_store3(path.exit_direction, t2);
  ends[id] = end;
  paths[id] = path;
}
