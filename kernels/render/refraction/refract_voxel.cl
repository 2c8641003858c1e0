/* refract_voxel.cl — voxel refraction (host/render/voxel_refraction.h): Chang & Lai TR 1688 §5 (two
 * surfaces) and PG 2011 §5 (multiple surfaces, Snell-law marching). A pixel whose
 * primary sample is a dielectric refracts there with the interpolated normal (exact), then marches the
 * voxel grids: the fine level (fitted to the dielectrics, or the whole scene's grid) and, after the path
 * leaves the fine grid's box, the coarse level (the whole scene). One work item per pixel of the list of
 * those (dielectric_pixels.cl): the ends and paths of the listed pixels are written, nothing else. The path
 * model is refraction.h's.
 *
 * The current level's grid units throughout the march (voxel (i, j, k) = [i, i+1] x [j, j+1] x [k, k+1]);
 * the grids are axis aligned, so directions are the same in world and grid frames and lengths scale by the
 * level's voxel_size. */
#include "grid_view.h"
#include "refraction_path.h"

#ifndef PATH_GROUP
#define PATH_GROUP 64
#endif

/* The voxel's unit normal, or the normals of its 3x3x3 neighbours of the same material (channel value
 * `material`) weighted by how close their centres are to q (smooth); zero where the writers' normals cancel.
 */
inline float3 boundary_normal(const GridView* g, int i, int j, int k, uint rank, uint material, float3 q,
                              uint smooth) {
  if (!smooth) return gv_normal(g, rank);
  float3 sum = (float3)(0.0f);
  for (int dk = -1; dk <= 1; ++dk)
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        const int a = i + di, b = j + dj, c = k + dk;
        if (!gv_contains(g, a, b, c)) continue;
        const ulong v = gv_linear(g, a, b, c);
        if (!gv_occupied(g, v)) continue;
        const uint r = gv_rank(g, v);
        if (gv_material(g, r) != material) continue;
        const float3 centre = (float3)((float)a + 0.5f, (float)b + 0.5f, (float)c + 0.5f);
        const float w = fmax(0.0f, 1.5f - length(centre - q));
        sum += w * gv_normal(g, r);
      }
  const float len = length(sum);
  return len > 1e-6f ? sum / len : gv_normal(g, rank);
}

/* One level of the grids: its view, frame and empty-space bricks. */
typedef struct Level {
  GridView g;
  float3 origin; /* anchor-relative world position of grid corner (0, 0, 0) */
  float voxel_size;
  uint brick_dims[3];
  __global const uint* bricks;
} Level;

inline Level level_make(GridView g, const VoxelLevelParams* lp, __global const uint* bricks) {
  Level l;
  l.g = g;
  l.origin = (float3)(lp->origin[0], lp->origin[1], lp->origin[2]);
  l.voxel_size = lp->voxel_size;
  for (int a = 0; a < 3; ++a) l.brick_dims[a] = lp->brick_dims[a];
  l.bricks = bricks;
  return l;
}

inline float3 to_world(const Level* l, float3 q) {
  return l->origin + l->voxel_size * q;
}

inline float3 to_level(const Level* l, float3 w) {
  return (w - l->origin) / l->voxel_size;
}

/* Beer-Lambert over the straight segment [from, to] (grid units) inside the innermost medium, if any: the
 * march applies it once per segment (at each event and at the end), not per voxel. */
inline void absorb_segment(float3* throughput, __global const RenderMaterial* materials,
                           const VoxrMedia* media, float3 from, float3 to, float voxel_size) {
  const uint top = voxr_media_top(media);
  if (top == VOXR_MEDIA_AIR) return;
  const float3 sigma = vload3(0, materials[top].absorption);
  *throughput *= exp(-sigma * (length(to - from) * voxel_size));
}

/* A march along one straight segment: the DDA's state, or the papers' sample point and step. */
typedef struct March {
  GvRay ray;   /* dda */
  float3 q;    /* papers: the current sample point (grid units) */
  float3 step; /* papers: dir / max |dir component| */
  float step_length;
  float3 origin, dir;
  int i, j, k; /* the current voxel */
  float t;     /* parameter (grid units along dir) where the current voxel was entered / sampled */
} March;

inline int march_begin(March* m, const GridView* g, float3 origin, float3 dir, uint dda) {
  m->origin = origin;
  m->dir = dir;
  m->t = 0.0f;
  if (dda) {
    if (!gv_ray_begin(&m->ray, g, origin, dir)) return 0;
    m->i = m->ray.i;
    m->j = m->ray.j;
    m->k = m->ray.k;
    m->t = m->ray.t;
    return 1;
  }
  const float3 a = fabs(dir);
  m->step_length = 1.0f / fmax(fmax(a.x, a.y), a.z);
  m->step = dir * m->step_length;
  m->q = origin;
  m->i = (int)floor(origin.x);
  m->j = (int)floor(origin.y);
  m->k = (int)floor(origin.z);
  return gv_contains(g, m->i, m->j, m->k);
}

/* march_begin for a new direction at a point of voxel (i, j, k), which stays the current voxel: after an
 * event the march goes on from the boundary voxel it happened in (floor() of a point on a voxel face could
 * pick the empty neighbour, leave the boundary run and meet the same surface again). */
inline void march_restart(March* m, const GridView* g, float3 origin, float3 dir, uint dda, int i, int j,
                          int k) {
  march_begin(m, g, origin, dir, dda);
  m->i = i;
  m->j = j;
  m->k = k;
  m->t = 0.0f;
  if (dda) {
    GvRay* r = &m->ray;
    r->i = i;
    r->j = j;
    r->k = k;
    gv_ray_steps(r, origin, dir, (float3)(1.0f) / dir);
    /* The origin may lie a hair outside voxel (i, j, k): no crossing before it. */
    r->tx = fmax(r->tx, 0.0f);
    r->ty = fmax(r->ty, 0.0f);
    r->tz = fmax(r->tz, 0.0f);
    r->t = 0.0f;
  }
}

/* The next voxel; 0 when the march leaves the grid. */
inline int march_step(March* m, const GridView* g, uint dda) {
  if (dda) {
    if (gv_ray_step(&m->ray, g) < 0) return 0;
    m->i = m->ray.i;
    m->j = m->ray.j;
    m->k = m->ray.k;
    m->t = m->ray.t;
    return 1;
  }
  m->q += m->step;
  m->t += m->step_length;
  m->i = (int)floor(m->q.x);
  m->j = (int)floor(m->q.y);
  m->k = (int)floor(m->q.z);
  return gv_contains(g, m->i, m->j, m->k);
}

inline float3 march_point(const March* m) {
  return m->origin + m->t * m->dir;
}

/* The point where the current segment entered voxel (m->i, m->j, m->k), no later than `here` and no earlier
 * than the segment's origin: the DDA's own t, the papers' step clipped back to the voxel's faces. */
inline float3 voxel_entry(const March* m, float3 here) {
  const float3 d = m->dir;
  const float3 lo = (float3)((float)m->i, (float)m->j, (float)m->k);
  float t = 0.0f;
  if (d.x != 0.0f) t = fmax(t, ((d.x > 0.0f ? lo.x : lo.x + 1.0f) - m->origin.x) / d.x);
  if (d.y != 0.0f) t = fmax(t, ((d.y > 0.0f ? lo.y : lo.y + 1.0f) - m->origin.y) / d.y);
  if (d.z != 0.0f) t = fmax(t, ((d.z > 0.0f ? lo.z : lo.z + 1.0f) - m->origin.z) / d.z);
  return m->origin + fmin(t, dot(here - m->origin, d)) * d;
}

/* Bit index of the brick holding voxel (i, j, k) (non-negative) in the empty-space grid of dims brick_dims.
 */
inline ulong brick_index(const uint* brick_dims, uint i, uint j, uint k) {
  return ((ulong)(k / VOXR_BRICK) * brick_dims[1] + j / VOXR_BRICK) * brick_dims[0] + i / VOXR_BRICK;
}

inline int brick_empty(const Level* l, int i, int j, int k) {
  const ulong brick = brick_index(l->brick_dims, (uint)i, (uint)j, (uint)k);
  return ((l->bricks[brick >> 5] >> (uint)(brick & 31)) & 1u) == 0u;
}

/* Where the segment m leaves the box [0, dims] of grid g, no earlier than its origin (grid units). */
inline float3 grid_exit(const March* m, const GridView* g) {
  const float3 o = m->origin, d = m->dir;
  const float3 hi = (float3)((float)g->dims_x, (float)g->dims_y, (float)g->dims_z);
  float t = INFINITY;
  if (d.x != 0.0f) t = fmin(t, ((d.x > 0.0f ? hi.x : 0.0f) - o.x) / d.x);
  if (d.y != 0.0f) t = fmin(t, ((d.y > 0.0f ? hi.y : 0.0f) - o.y) / d.y);
  if (d.z != 0.0f) t = fmin(t, ((d.z > 0.0f ? hi.z : 0.0f) - o.z) / d.z);
  return o + fmax(t, 0.0f) * d;
}

/* The ray parameter where origin + t dir leaves brick box [lo, lo + VOXR_BRICK]^3, >= 0. Components under
 * 1e-6 count as parallel: a ray running along a brick face would otherwise "leave" it at t = 0 forever. */
inline float brick_exit(float3 origin, float3 dir, int i, int j, int k) {
  const float3 lo = (float3)((float)(i / VOXR_BRICK * VOXR_BRICK), (float)(j / VOXR_BRICK * VOXR_BRICK),
                             (float)(k / VOXR_BRICK * VOXR_BRICK));
  const float3 hi = lo + (float3)((float)VOXR_BRICK);
  float t = INFINITY;
  if (fabs(dir.x) > 1e-6f) t = fmin(t, ((dir.x > 0.0f ? hi.x : lo.x) - origin.x) / dir.x);
  if (fabs(dir.y) > 1e-6f) t = fmin(t, ((dir.y > 0.0f ? hi.y : lo.y) - origin.y) / dir.y);
  if (fabs(dir.z) > 1e-6f) t = fmin(t, ((dir.z > 0.0f ? hi.z : lo.z) - origin.z) / dir.z);
  return fmax(t, 0.0f);
}

inline int same_brick(float3 q, int i, int j, int k) {
  const int3 v = convert_int3(floor(q));
  return v.x >= 0 && v.y >= 0 && v.z >= 0 && v.x / VOXR_BRICK == i / VOXR_BRICK &&
         v.y / VOXR_BRICK == j / VOXR_BRICK && v.z / VOXR_BRICK == k / VOXR_BRICK;
}

/* The fine level's view is VOXR_GRID_VIEW_PARAMS, the coarse level's VOXR_GRID_VIEW_PARAMS_NAMED(coarse)
 * (the fine one again, unread, when p.coarse.present is 0). */
__kernel __attribute__((reqd_work_group_size(PATH_GROUP, 1, 1))) void refract_voxel(
    VOXR_GRID_VIEW_PARAMS, VOXR_GRID_VIEW_PARAMS_NAMED(coarse), RenderCamera cam,
    __global const SurfaceSample* primary, __global const uint* pixel_list, __global const uint* pixel_count,
    __global const RenderMaterial* materials, uint material_count, VoxelRefractParams p,
    __global const uint* fine_bricks, __global const uint* coarse_bricks, __global const uint* material_of,
    __global SurfaceSample* ends, __global RefractionPath* paths) {
  uint id;
  if (!rp_listed_pixel(pixel_list, pixel_count, get_global_id(0), &id)) return;
  const Level fine = level_make(VOXR_GRID_VIEW(), &p.fine, fine_bricks);
  const Level coarse = level_make(VOXR_GRID_VIEW_NAMED(coarse), &p.coarse, coarse_bricks);
  const Level* l = &fine; /* the level marched now */
  float3 dir = rp_camera_direction(&cam, id % cam.width, id / cam.width);
  const SurfaceSample s = primary[id];
  RefractionPath path;
  float3 t_dir;
  float cos_i;
  rp_front_surface(s, dir, materials, material_count, &path, &t_dir, &cos_i);
  const uint m0 = min(s.material, material_count - 1u);
  const float3 n_front = vload3(0, s.normal);
  float3 throughput = (float3)(1.0f - path.fresnel);
  uint events = 1u;
  dir = t_dir;
  float3 exit_world = vload3(0, s.position);

  VoxrMedia media = rp_media_front(m0);
  float3 prev_normal = n_front;
  uint run_material = m0;
  int in_run = 1; /* inside the boundary run last refracted at */

  const float3 origin = to_level(l, exit_world);
  March m;
  int inside_grid = march_begin(&m, &l->g, origin, dir, p.step_dda);
  float3 last = origin; /* where absorption was last accounted */
  int ended = 0;
  SurfaceSample end = rp_no_surface();
  /* Voxel normals follow the mesh's winding, the front normal faces the eye: give the run test the voxels'
   * orientation, or a mesh wound inwards would see its own front shell as the next surface. */
  if (inside_grid) {
    const ulong v0 = gv_linear(&l->g, m.i, m.j, m.k);
    if (gv_occupied(&l->g, v0) && dot(gv_normal(&l->g, gv_rank(&l->g, v0)), prev_normal) < 0.0f)
      prev_normal = -prev_normal;
  }
  int examine_current = 0; /* after a skip the voxel begun in is examined before stepping on */
  for (uint steps = 0; steps < p.max_steps; ++steps) {
    if (!inside_grid || (!examine_current && !march_step(&m, &l->g, p.step_dda))) {
      if (l == &coarse || !p.coarse.present) {
        inside_grid = 0;
        break;
      }
      /* Out of the fine grid's box: the march goes on in the coarse level from where it left the box.
       * Every dielectric lies in that box and the path is straight from here on (the coarse level has no
       * refraction events), so it never comes back into the box. */
      const float3 w = to_world(l, grid_exit(&m, &l->g));
      last = to_level(&coarse, to_world(l, last));
      l = &coarse;
      in_run = 0;
      inside_grid = march_begin(&m, &l->g, to_level(l, w), dir, p.step_dda);
      examine_current = 1;
      continue;
    }
    examine_current = 0;
    const float3 here = march_point(&m);
    const ulong v = gv_linear(&l->g, m.i, m.j, m.k);
    if (!gv_occupied(&l->g, v)) {
      in_run = 0;
      if (brick_empty(l, m.i, m.j, m.k)) {
        /* Skip the rest of the empty brick: restart the march just past its exit. */
        const float3 beyond = here + (brick_exit(here, dir, m.i, m.j, m.k) + 1e-3f) * dir;
        if (!same_brick(beyond, m.i, m.j, m.k)) { /* else step on voxel by voxel: no progress to gain */
          inside_grid = march_begin(&m, &l->g, beyond, dir, p.step_dda);
          examine_current = 1;
        }
      }
      continue;
    }
    const uint rank = gv_rank(&l->g, v);
    /* The material channel holds the priority rank the host voxelized (voxel_refraction.h): back to the
     * scene's material index. */
    const uint stored = min(gv_material(&l->g, rank), material_count - 1u);
    const uint mat = material_of[stored];
    const RenderMaterial mm = materials[mat];
    if (mm.kind == VOXR_MATERIAL_OPAQUE) {
      absorb_segment(&throughput, materials, &media, last, here, l->voxel_size);
      float3 n = boundary_normal(&l->g, m.i, m.j, m.k, rank, stored, here, p.smooth_normals);
      if (dot(n, n) < 1e-12f) n = -dir;
      if (dot(n, dir) > 0.0f) n = -n;
      /* Where the ray entered the voxel (the papers' sample point may lie inside the opaque object). */
      rp_store3(end.position, to_world(l, voxel_entry(&m, here)));
      end.triangle = VOXR_VOXEL_HIT;
      rp_store3(end.normal, n);
      end.material = mat;
      rp_store3(end.geometric_normal, n);
      ended = 1;
      break;
    }
    if (mm.kind == VOXR_MATERIAL_SHEET) {
      if (!in_run || run_material != mat) throughput *= vload3(0, mm.transmittance);
      in_run = 1;
      run_material = mat;
      continue;
    }
    /* A dielectric boundary voxel. On the coarse level the path is outside the fine box, which holds every
     * dielectric triangle: the voxel's glass lies in the box, beside the ray. */
    if (l == &coarse) continue;
    if (p.two_surface && (events >= 2u || mat != m0)) continue; /* voxel-two: only its object's back */
    const float3 n_voxel = gv_normal(&l->g, rank);
    if (dot(n_voxel, n_voxel) < 1e-12f)
      continue; /* the writers' normals cancel: glass thinner than a voxel */
    /* The surface refracted at last: its boundary run, or a voxel of it within two voxels of the event (a
     * conservative surface is not a 6-connected run along every ray), unless the normal turns by more than
     * the angle threshold (PG 2011): then it is the next surface, e.g. the far side of a thin part. */
    const int near_last = in_run || length(here - last) < 2.0f;
    if (near_last && run_material == mat && dot(n_voxel, prev_normal) > p.cos_threshold) continue;
    const float3 n =
        p.smooth_normals ? boundary_normal(&l->g, m.i, m.j, m.k, rank, stored, here, 1u) : n_voxel;
    absorb_segment(&throughput, materials, &media, last, here, l->voxel_size);
    last = here;
    float3 new_dir;
    /* Entered or left by the voxel's normal: a sum of its triangles' winding normals, outward. */
    if (!rp_interface(dir, n, dot(dir, n_voxel), mat, &media, materials, &throughput, &events, &new_dir)) {
      ended = 1;
      break;
    }
    if (p.two_surface && (events & VOXR_PATH_EVENTS_MASK) >= 2u)
      media = voxr_media_empty(); /* passes all later glass */
    prev_normal = n_voxel;
    run_material = mat;
    in_run = 1;
    exit_world = to_world(l, here);
    if ((events & VOXR_PATH_EVENTS_MASK) >= VOXR_PATH_MAX_EVENTS) {
      events |= VOXR_PATH_LOST;
      ended = 1;
      break;
    }
    dir = new_dir;
    march_restart(&m, &l->g, here, dir, p.step_dda, m.i, m.j, m.k);
  }
  if (!ended) {
    absorb_segment(&throughput, materials, &media, last, march_point(&m), l->voxel_size);
    if (inside_grid && media.depth > 0u)
      events |= VOXR_PATH_LOST; /* out of steps inside glass */
    else
      events |= VOXR_PATH_ENV;
  }
  rp_store3(path.throughput, throughput);
  path.events = events;
  rp_store3(path.exit_position, exit_world);
  rp_store3(path.exit_direction, dir);
  ends[id] = end;
  paths[id] = path;
}
