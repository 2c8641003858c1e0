/* distance_maps.cl — refraction by layered distance maps (host/render/distance_map_refraction.h): GPU Gems 3,
 * chapter 17 (Umenhoffer, Patow, Szirmay-Kalos 2007). One work item per pixel that sees a dielectric (the
 * list of dielectric_pixels.cl; only those pixels' ends and paths are written): its primary sample
 * refracts there (rp_front_surface) and then, segment by segment, searches the cube maps
 * about the reference point for the ray's next surface: the linear search steps along the ray and, per map
 * (each refractor layer and the environment layer), compares the ray point's distance from the reference
 * point with the distance the map stores in the point's direction (nearest texel); a sign change between
 * two steps is refined by secant steps and accepted where the refined gap is within a step plus a texel's
 * footprint (else the sign changed at a depth discontinuity of the map), is not on the triangle the ray
 * leaves, and lies at least half a texel's footprint away from where it leaves. The nearest accepted hit
 * wins: a refractor layer's is a dielectric interface (refraction.h's model: Snell with the layer's shading
 * normal, 1 - F per refraction, total internal reflection mirrors, Beer-Lambert per segment, media on
 * the stack of media_stack.h, entered or left by the winding of the triangle a layer texel holds), the
 * environment layer's ends the path on that surface. Outside every medium and past the refractor's sphere the
 * environment layer alone is searched to the scene's sphere; nothing found there is the environment, nothing
 * found inside a medium is VOXR_PATH_LOST (the maps miss a surface). The searches read each map's distances
 * alone (dm_distances: one float per texel, -1 where empty, the refractor layers then the environment layer),
 * the samples only at hits.
 *   dm_distances: distances[first + i] from samples[i]. shape: one work item per texel.
 *   distance_maps: the tracing. shape: one work item per pixel.
 * in:  camera, primary samples (width * height), refractor layers (layers * 6 * layer_res^2 SurfaceSample),
 *      environment layer (6 * layer_res^2), their distances ((layers + 1) * 6 * layer_res^2), materials,
 *      the mesh the layers were rasterized from (positions float4, triangles uint4)
 * out: ends[pixel] (SurfaceSample), paths[pixel] (RefractionPath) */
#include "refraction_path.h"

#ifndef PATH_GROUP
#define PATH_GROUP 64
#endif

#define DM_MAX_MAPS 17 /* kDistanceMapMaxLayers refractor layers and the environment layer */

__constant float dm_faces[6][9] = VOXR_CUBE_FACES;

/* The texel (face, row, column) of direction v (non-zero) from the reference point. */
inline uint dm_texel(const DistanceMapParams* p, float3 v) {
  const float3 a = fabs(v);
  uint face;
  if (a.x >= a.y && a.x >= a.z)
    face = v.x >= 0.0f ? 0u : 1u;
  else if (a.y >= a.z)
    face = v.y >= 0.0f ? 2u : 3u;
  else
    face = v.z >= 0.0f ? 4u : 5u;
  __constant const float* f = dm_faces[face];
  const float z = v.x * f[0] + v.y * f[1] + v.z * f[2];
  const float sx = (v.x * f[3] + v.y * f[4] + v.z * f[5]) / z;
  const float sy = (v.x * f[6] + v.y * f[7] + v.z * f[8]) / z;
  const float res = (float)p->layer_res;
  const uint x = min((uint)fmax((sx + 1.0f) * 0.5f * res, 0.0f), p->layer_res - 1u);
  const uint y = min((uint)fmax((1.0f - sy) * 0.5f * res, 0.0f), p->layer_res - 1u);
  return (face * p->layer_res + y) * p->layer_res + x;
}

/* Map m: refractor layer m, or the environment layer for m == layers. */
inline __global const SurfaceSample* dm_map(__global const SurfaceSample* layers,
                                            __global const SurfaceSample* environment,
                                            const DistanceMapParams* p, uint m) {
  return m < p->layers ? layers + (ulong)m * 6u * p->layer_res * p->layer_res : environment;
}

__kernel __attribute__((reqd_work_group_size(PATH_GROUP, 1, 1))) void dm_distances(
    __global const SurfaceSample* samples, uint count, ulong first, __global float* distances) {
  const uint i = get_global_id(0);
  if (i >= count) return;
  distances[first + i] = samples[i].triangle == VOXR_NO_TRIANGLE ? -1.0f : samples[i].distance;
}

/* Map m's distances: refractor layer m, or the environment layer for m == layers. */
inline __global const float* dm_distance_map(__global const float* distances, const DistanceMapParams* p,
                                             uint m) {
  return distances + (ulong)m * 6u * p->layer_res * p->layer_res;
}

/* The gap of point q against a map: |q - ref| minus the map's distance in q's direction. Returns 0 where
 * the map has no surface in that direction. */
inline int dm_gap(__global const float* map, const DistanceMapParams* p, float3 ref, float3 q, float* gap,
                  uint* texel) {
  const float3 v = q - ref;
  const uint t = dm_texel(p, v);
  const float stored = map[t];
  if (stored < 0.0f) return 0;
  *gap = length(v) - stored;
  *texel = t;
  return 1;
}

/* Secant refinement of a sign change of a map's gap between ray parameters ta (gap ga) and tb (gap gb).
 * Returns 1 with the refined parameter and its texel where the last gap is within tol. */
inline int dm_secant(__global const float* map, const DistanceMapParams* p, float3 ref, float3 o, float3 d,
                     float ta, float ga, float tb, float gb, float tol, float* t_hit, uint* texel_hit) {
  int have = 0;
  float t = ta, g = ga;
  uint texel = 0u;
  for (uint k = 0; k < p->secant_steps; ++k) {
    const float tn = ta + (tb - ta) * ga / (ga - gb);
    float gn;
    uint tx;
    if (!dm_gap(map, p, ref, o + tn * d, &gn, &tx)) break;
    have = 1;
    t = tn;
    g = gn;
    texel = tx;
    if (gn == 0.0f) break;
    if ((gn < 0.0f) == (ga < 0.0f)) {
      ta = tn;
      ga = gn;
    } else {
      tb = tn;
      gb = gn;
    }
  }
  if (!have || !(fabs(g) <= tol)) return 0;
  *t_hit = t;
  *texel_hit = texel;
  return 1;
}

/* The linear search: the nearest accepted crossing of maps m_lo..m_hi along o + t d for t in
 * [t_begin, t_end], in p->search_steps steps. Hits on triangle `left` or nearer than min_t are rejected.
 * Returns 1 with the hit's parameter, map and texel. */
inline int dm_search(__global const SurfaceSample* layers, __global const SurfaceSample* environment,
                     __global const float* distances, const DistanceMapParams* p, float3 ref, float3 o,
                     float3 d, float t_begin, float t_end, uint m_lo, uint m_hi, uint left, float min_t,
                     float* t_hit, uint* map_hit, uint* texel_hit) {
  if (!(t_end > t_begin)) return 0;
  float gap_before[DM_MAX_MAPS];
  int valid_before[DM_MAX_MAPS];
  uint texel;
  for (uint m = m_lo; m <= m_hi; ++m)
    valid_before[m - m_lo] =
        dm_gap(dm_distance_map(distances, p, m), p, ref, o + t_begin * d, &gap_before[m - m_lo], &texel);
  const uint steps = max(p->search_steps, 1u);
  const float dt = (t_end - t_begin) / (float)steps;
  for (uint k = 1; k <= steps; ++k) {
    const float ta = t_begin + (float)(k - 1u) * dt, tb = t_begin + (float)k * dt;
    const float3 q = o + tb * d;
    const float tol = dt + 4.0f * length(q - ref) / (float)p->layer_res;
    int found = 0;
    float best = INFINITY;
    for (uint m = m_lo; m <= m_hi; ++m) {
      __global const float* map = dm_distance_map(distances, p, m);
      float g = 0.0f;
      const int valid = dm_gap(map, p, ref, q, &g, &texel);
      const uint i = m - m_lo;
      if (valid && valid_before[i] && (g < 0.0f) != (gap_before[i] < 0.0f)) {
        float th;
        uint tx;
        if (dm_secant(map, p, ref, o, d, ta, gap_before[i], tb, g, tol, &th, &tx) && th >= min_t &&
            th < best && dm_map(layers, environment, p, m)[tx].triangle != left) {
          best = th;
          *map_hit = m;
          *texel_hit = tx;
          found = 1;
        }
      }
      valid_before[i] = valid;
      gap_before[i] = g;
    }
    if (found) {
      *t_hit = best;
      return 1;
    }
  }
  return 0;
}

/* Where the ray v + t d (v relative to the sphere's centre, d unit) leaves the sphere of radius r; <= 0
 * when it does not lie ahead. */
inline float dm_sphere_exit(float3 v, float3 d, float r) {
  const float b = dot(v, d);
  const float c = dot(v, v) - r * r;
  return -b + sqrt(fmax(b * b - c, 0.0f));
}

__kernel __attribute__((reqd_work_group_size(PATH_GROUP, 1, 1))) void distance_maps(
    RenderCamera cam, __global const SurfaceSample* primary, __global const uint* pixel_list,
    __global const uint* pixel_count, __global const SurfaceSample* layers,
    __global const SurfaceSample* environment, __global const float* distances,
    __global const RenderMaterial* materials, uint material_count, DistanceMapParams p,
    __global const float4* positions, __global const uint4* triangles, __global SurfaceSample* ends,
    __global RefractionPath* paths) {
  uint id;
  if (!rp_listed_pixel(pixel_list, pixel_count, get_global_id(0), &id)) return;
  const float3 camera_dir = rp_camera_direction(&cam, id % cam.width, id / cam.width);
  const SurfaceSample s = primary[id];
  RefractionPath path;
  float3 d;
  float cos_i;
  rp_front_surface(s, camera_dir, materials, material_count, &path, &d, &cos_i);
  float3 throughput = (float3)(1.0f - path.fresnel);
  uint events = 1u;
  float3 o = vload3(0, s.position);
  float3 exit = o;
  uint left = s.triangle;
  VoxrMedia media = rp_media_front(min(s.material, material_count - 1u));
  const float3 ref = vload3(0, p.reference);
  const uint env_map = p.layers;
  SurfaceSample end = rp_no_surface();

  for (;;) {
    const float3 v = o - ref;
    const float t_refractor = dm_sphere_exit(v, d, p.radius);
    const float min_t = length(v) / (float)p.layer_res; /* half a texel's footprint where the ray leaves */
    float t;
    uint m, texel;
    int hit = dm_search(layers, environment, distances, &p, ref, o, d, p.epsilon, t_refractor, 0u, env_map,
                        left, min_t, &t, &m, &texel);
    const uint top = voxr_media_top(&media);
    if (!hit && top == VOXR_MEDIA_AIR)
      hit = dm_search(layers, environment, distances, &p, ref, o, d, fmax(p.epsilon, t_refractor),
                      dm_sphere_exit(v, d, p.scene_radius), env_map, env_map, left, min_t, &t, &m, &texel);
    if (!hit) {
      events |= top != VOXR_MEDIA_AIR ? VOXR_PATH_LOST : VOXR_PATH_ENV;
      break;
    }
    if (top != VOXR_MEDIA_AIR) throughput *= exp(-vload3(0, materials[top].absorption) * t);
    const SurfaceSample h = dm_map(layers, environment, &p, m)[texel];
    if (m == env_map) {
      /* The map turned its normals towards the reference point; the path meets the surface along d. */
      end = h;
      const float3 ng = vload3(0, h.geometric_normal);
      if (dot(ng, d) > 0.0f) {
        rp_store3(end.geometric_normal, -ng);
        rp_store3(end.normal, -vload3(0, h.normal));
      }
      break;
    }
    /* A dielectric interface, entered or left by its triangle's winding (the map turned its normals). */
    const float3 here = o + t * d;
    const uint mat = min(h.material, material_count - 1u);
    const uint4 tri = triangles[h.triangle];
    const float3 p0 = positions[tri.x].xyz;
    const float facing = dot(d, cross(positions[tri.y].xyz - p0, positions[tri.z].xyz - p0));
    float3 next;
    if (!rp_interface(d, vload3(0, h.normal), facing, mat, &media, materials, &throughput, &events, &next))
      break;
    exit = here;
    if ((events & VOXR_PATH_EVENTS_MASK) >= p.max_events) {
      events |= VOXR_PATH_LOST;
      break;
    }
    d = next;
    o = here;
    left = h.triangle;
  }

  rp_store3(path.throughput, throughput);
  path.events = events;
  rp_store3(path.exit_position, exit);
  rp_store3(path.exit_direction, d);
  ends[id] = end;
  paths[id] = path;
}
