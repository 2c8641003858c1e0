/* refract_exact.cl — `--refraction voxel-exact` (host/render/techniques/voxel_exact_refraction.cpp): the
 * matched reference's path model (host/reference/reference_refraction.cpp, refract_voxel.cl's optics) on
 * the exact triangles, found through the per-voxel triangle lists (triangle_grid.h) instead of a BVH. Per
 * pixel of the list of those whose primary sample is a dielectric (dielectric_pixels.cl): refract at the
 * exact front surface (rp_front_surface), then repeatedly find the nearest triangle along the ray
 * (tg_nearest_hit_leaving: the triangles just left are skipped, their vertex-sharing neighbours only within
 * `coincide` of the origin, every other surface counts from `coincide` behind it, so a floor coplanar with a
 * glass face is met whichever side of it rounding put the point; among coincident hits an opaque one wins,
 * then the lowest id: the reference's ReferenceScene::intersect_leaving), absorb along the segment inside the
 * innermost medium (Beer-Lambert), and at a dielectric refract by Snell's law with the interpolated shading
 * normal (surface_normal.h), Schlick 1 - F, total internal reflection, the media stack
 * (media_stack.h: entered or left by the triangle's winding); a sheet
 * multiplies its transmittance; an opaque hit ends the path with its SurfaceSample (triangle, barycentrics,
 * normals), which the shadow lookup and shading treat like any surface. Nothing: the environment. in:  the
 * triangle grid, camera, primary samples, the pixel list and its count, materials, vertex normals (float4),
 * the coincidence tolerance (world units) out: ends[id], paths[id] of listed pixels only shape: one work item
 * per listed pixel. */
#include "refraction_path.h"
#include "surface_normal.h"
#include "triangle_grid.h"

#ifndef PATH_GROUP
#define PATH_GROUP 64
#endif
/* Surfaces met along one path at most (sheets included), as the reference's kMaxSegments. */
#define MAX_SEGMENTS 4096
/* Triangles a ray leaves at one point at most (the reference's Leaving). */
#define MAX_LEAVING 8

/* The SurfaceSample of hit h of the ray origin + t dir (unit dir). */
inline SurfaceSample exact_sample(const TriangleGridView* tg, __global const float4* normals, const TgHit* h,
                                  float3 origin, float3 dir) {
  const uint4 tri = tg->triangles[h->triangle];
  float3 ns, ng;
  sn_normals(tg->positions[tri.x].xyz, tg->positions[tri.y].xyz, tg->positions[tri.z].xyz, normals[tri.x].xyz,
             normals[tri.y].xyz, normals[tri.z].xyz, h->b1, h->b2, dir, &ns, &ng);
  SurfaceSample s;
  rp_store3(s.position, origin + h->t * dir);
  s.triangle = h->triangle;
  rp_store3(s.normal, ns);
  s.material = tri.w;
  rp_store3(s.geometric_normal, ng);
  s.distance = fmax(h->t, 0.0f); /* a coincident surface may be met a hair behind the origin */
  s.barycentric[0] = h->b1;
  s.barycentric[1] = h->b2;
  s.pad[0] = s.pad[1] = 0.0f;
  return s;
}

__kernel __attribute__((reqd_work_group_size(PATH_GROUP, 1, 1))) void refract_exact(
    VOXR_TRIANGLE_GRID_PARAMS, RenderCamera cam, __global const SurfaceSample* primary,
    __global const uint* pixel_list, __global const uint* pixel_count,
    __global const RenderMaterial* materials, uint material_count, __global const float4* normals,
    float coincide, __global SurfaceSample* ends, __global RefractionPath* paths) {
  uint id;
  if (!rp_listed_pixel(pixel_list, pixel_count, get_global_id(0), &id)) return;
  const TriangleGridView tg = VOXR_TRIANGLE_GRID();
  float3 dir = rp_camera_direction(&cam, id % cam.width, id / cam.width);
  const SurfaceSample s = primary[id];
  RefractionPath path;
  float3 t_dir;
  float cos_i;
  rp_front_surface(s, dir, materials, material_count, &path, &t_dir, &cos_i);
  const uint m0 = min(s.material, material_count - 1u);
  float3 throughput = (float3)(1.0f - path.fresnel);
  uint events = 1u;
  dir = t_dir;
  float3 here = vload3(0, s.position), exit = here;
  /* The triangles the ray leaves: the one it left, and before it those met at the same point (a coincident
   * surface passed within `coincide`), as the reference's Leaving. */
  uint leaving[MAX_LEAVING];
  uint leaving_count = 1u;
  leaving[0] = s.triangle;
  VoxrMedia media = rp_media_front(m0);

  SurfaceSample end = rp_no_surface();
  int ended = 0;
  for (uint segment = 0;; ++segment) {
    if (segment >= MAX_SEGMENTS) {
      events |= VOXR_PATH_LOST;
      ended = 1;
      break;
    }
    TgHit h;
    if (!tg_nearest_hit_leaving(&tg, here, dir, -coincide, INFINITY, leaving, leaving_count, coincide,
                                materials, coincide, &h))
      break;
    const SurfaceSample hit = exact_sample(&tg, normals, &h, here, dir);
    const uint top = voxr_media_top(&media);
    if (top != VOXR_MEDIA_AIR) throughput *= exp(-vload3(0, materials[top].absorption) * hit.distance);
    here = vload3(0, hit.position);
    if (hit.distance <= coincide && leaving_count < MAX_LEAVING) {
      leaving[leaving_count++] = h.triangle;
    } else {
      leaving[0] = h.triangle;
      leaving_count = 1u;
    }
    const uint mat = min(h.material, material_count - 1u);
    const RenderMaterial mm = materials[mat];
    if (mm.kind == VOXR_MATERIAL_OPAQUE) {
      end = hit;
      ended = 1;
      break;
    }
    if (mm.kind == VOXR_MATERIAL_SHEET) {
      throughput *= vload3(0, mm.transmittance);
      continue;
    }
    /* Entered or left by the triangle's winding (its outward normal), not the normal turned to the ray. */
    const uint4 tri = tg.triangles[h.triangle];
    const float3 p0 = tg.positions[tri.x].xyz;
    const float facing = dot(dir, cross(tg.positions[tri.y].xyz - p0, tg.positions[tri.z].xyz - p0));
    float3 new_dir;
    if (!rp_interface(dir, vload3(0, hit.normal), facing, mat, &media, materials, &throughput, &events,
                      &new_dir)) {
      ended = 1;
      break;
    }
    exit = here;
    if ((events & VOXR_PATH_EVENTS_MASK) >= VOXR_PATH_MAX_EVENTS) {
      events |= VOXR_PATH_LOST;
      ended = 1;
      break;
    }
    dir = new_dir;
  }
  if (!ended) events |= VOXR_PATH_ENV;
  rp_store3(path.throughput, throughput);
  path.events = events;
  rp_store3(path.exit_position, exit);
  rp_store3(path.exit_direction, dir);
  ends[id] = end;
  paths[id] = path;
}
