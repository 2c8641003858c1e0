/* shadow_exact.cl — `--shadows voxel-exact`: each receiver's transmittance along the straight segment to the
 * light, through the per-voxel triangle lists (triangle_grid.h), computed as ReferenceScene::transmittance
 * computes it (host/reference/reference_scene.h): no light-space map.
 *
 * Per sample with a triangle (a dielectric sample, shaded flat, and one without a triangle get 1): the ray
 * from the sample's position towards the light (a point light's position, or against a directional light's
 * direction) is marched voxel by voxel (3-D DDA; empty 8^3 bricks in one step) to the grid's exit — past a
 * point light too, where only the dielectrics' crossings count (they say whether the receiver lies
 * inside one). In each occupied voxel every listed triangle but the receiver's own is intersected (watertight
 * test); a hit is kept beyond VOXR_SHADOW_START_EPSILON x `scene_size` (shadow_tolerances.h: the reference's
 * kStartEpsilon) and within the voxel's [t_enter, t_exit] widened by VOXR_EXACT_SHADOW_TOLERANCE voxels (a
 * triangle listed in two voxels is kept once).
 *
 * Hits are grouped as the reference groups them: hits less than `merge` = VOXR_SHADOW_MERGE_DISTANCE x
 * `scene_size` apart on triangles sharing a vertex index, transitively, are one meeting of the ray with one
 * surface (at an edge or a vertex). Groups are closed as soon as no later hit can join them (the march has
 * passed their last hit by `merge`), in the order of their first hit, so only the hits of the groups still
 * open are kept. A group where the ray only touches the surface (a shared edge whose two faces lie on one
 * side, seen along the ray; a vertex whose faces face the ray with both sides) is no crossing; any other is
 * one crossing of each distinct material in it, at its first hit: before the light an opaque crossing gives 0
 * (the march stops), a sheet multiplies its transmittance; a dielectric's crossing enters or leaves its
 * material by the winding of the group's first face of it, wherever it is.
 * Every start depth is accumulated in one pass (media_stack.h VoxrSolidLedger: per dielectric material the
 * length before the light at each sum of the crossings' signs, and the parity fallback's alternating sum)
 * and the whole ray's sum picks one at the end: the ray ends outside everything, so the depth at the
 * receiver is minus that sum (parity for an open or inside-out mesh); the lengths inside multiply by
 * exp(-sigma_a x length).
 *
 * Limits (both far above the scenes': a lost hit or material changes the result, never its determinism):
 * VOXR_EXACT_SHADOW_WINDOW open hits (a full window closes its first group at once), VOXR_EXACT_SHADOW_SOLIDS
 * distinct dielectric materials per ray (more are not attenuated), VOXR_EXACT_SHADOW_GROUP distinct faces
 * and materials per group.
 * One work item per sample, deterministic (each ray's arithmetic is its own, in a fixed order). */
#include "media_stack.h"
#include "shadow_tolerances.h"
#include "triangle_grid.h"

#ifndef SHADOW_GROUP
#define SHADOW_GROUP 64
#endif
#ifndef VOXR_EXACT_SHADOW_WINDOW
#define VOXR_EXACT_SHADOW_WINDOW 32
#endif
#ifndef VOXR_EXACT_SHADOW_SOLIDS
#define VOXR_EXACT_SHADOW_SOLIDS 8
#endif
#ifndef VOXR_EXACT_SHADOW_GROUP
#define VOXR_EXACT_SHADOW_GROUP 8
#endif
/* In voxels: how far outside a voxel's [t_enter, t_exit] a hit on one of its triangles is still kept (the
 * hit's t and the voxel's boundaries are rounded differently). */
#ifndef VOXR_EXACT_SHADOW_TOLERANCE
#define VOXR_EXACT_SHADOW_TOLERANCE 1e-3f
#endif

/* What the mesh and the materials say to the crossings. */
typedef struct SxScene {
  __global const float4* positions;
  __global const uint4* triangles; /* xyz: vertex indices, w: material */
  __global const RenderMaterial* materials;
  uint material_count;
  float merge; /* world distance below which hits on triangles sharing a vertex are one meeting */
} SxScene;

/* One ray's crossings so far. */
typedef struct SxState {
  float3 dir;    /* unit, towards the light */
  float t_end;   /* the light's distance (INFINITY: directional) */
  float3 sheets; /* product of the sheets' transmittance before the light */
  int blocked;   /* an opaque crossing before the light */
  uint solids;
  VoxrSolidLedger solid[VOXR_EXACT_SHADOW_SOLIDS]; /* per dielectric material met (media_stack.h) */
  uint open;                                       /* hits kept, sorted by (t, triangle) */
  float hit_t[VOXR_EXACT_SHADOW_WINDOW];
  uint hit_triangle[VOXR_EXACT_SHADOW_WINDOW];
} SxState;

inline float3 sx_position(const SxScene* sc, uint vertex) {
  return sc->positions[vertex].xyz;
}

/* cross(p1 - p0, p2 - p0) of triangle tri (its winding's normal, unnormalized). */
inline float3 sx_face_normal(const SxScene* sc, uint4 tri) {
  const float3 p0 = sx_position(sc, tri.x);
  return cross(sx_position(sc, tri.y) - p0, sx_position(sc, tri.z) - p0);
}

/* The vertex set of a triangle, sorted: two triangles with one set are one face. */
inline uint3 sx_face_key(uint4 tri) {
  const uint a = min(tri.x, tri.y), b = max(tri.x, tri.y);
  const uint lo = min(a, tri.z), hi = max(b, tri.z);
  return (uint3)(lo, tri.x + tri.y + tri.z - lo - hi, hi);
}

/* Whether the ray crosses the surface at one point shared by `count` distinct faces (ReferenceScene's
 * crosses, in float): two faces sharing an edge, by the sides their third vertices lie on seen along the
 * ray; otherwise by the faces' windings. */
inline int sx_crosses(const SxScene* sc, const uint4* faces, uint count, float3 d) {
  if (count < 2) return 1;
  if (count == 2) {
    const uint4 a = faces[0], b = faces[1];
    uint shared[3], n = 0, third_a = 0, third_b = 0;
    const uint av[3] = {a.x, a.y, a.z}, bv[3] = {b.x, b.y, b.z};
    for (int i = 0; i < 3; ++i) {
      const int in_b = av[i] == bv[0] || av[i] == bv[1] || av[i] == bv[2];
      if (in_b)
        shared[n++] = av[i];
      else
        third_a = av[i];
    }
    if (n == 2) {
      for (int j = 0; j < 3; ++j)
        if (bv[j] != shared[0] && bv[j] != shared[1]) third_b = bv[j];
      const float3 e0 = sx_position(sc, shared[0]), edge = sx_position(sc, shared[1]) - e0;
      const float side_a = dot(d, cross(edge, sx_position(sc, third_a) - e0));
      const float side_b = dot(d, cross(edge, sx_position(sc, third_b) - e0));
      return !((side_a > 0.0f && side_b > 0.0f) ||
               (side_a < 0.0f && side_b < 0.0f)); /* signs: no underflow */
    }
  }
  int front = 0, back = 0;
  for (uint f = 0; f < count; ++f) {
    const float facing = dot(d, sx_face_normal(sc, faces[f]));
    front = front || facing < 0.0f;
    back = back || facing > 0.0f;
  }
  return !(front && back);
}

/* One crossing of `material` at distance t, entering it (its face's winding normal faces the ray) or not. */
inline void sx_event(SxState* st, const SxScene* sc, float t, uint material, int enters) {
  const RenderMaterial m = sc->materials[min(material, sc->material_count - 1u)];
  const int before = t < st->t_end;
  if (m.kind == VOXR_MATERIAL_OPAQUE) {
    st->blocked = st->blocked || before;
  } else if (m.kind == VOXR_MATERIAL_SHEET) {
    if (before) st->sheets *= vload3(0, m.transmittance);
  } else {
    uint s = 0;
    while (s < st->solids && st->solid[s].material != material) ++s;
    if (s == st->solids) {
      if (s == VOXR_EXACT_SHADOW_SOLIDS) return;
      st->solid[s] = voxr_ledger_make(material);
      ++st->solids;
    }
    voxr_ledger_cross(&st->solid[s], t, enters, before);
  }
}

/* Closes the open groups no hit at t >= bound can join, in the order of their first hits, up to the first
 * that may still grow; `bound` = INFINITY closes them all, `force` closes the first whatever `bound` says. */
inline void sx_close(SxState* st, const SxScene* sc, float bound, int force) {
  while (st->open > 0) {
    /* The group of the first open hit: every hit linked to it (less than `merge` apart, a shared vertex),
     * transitively, to a fixed point. */
    uchar member[VOXR_EXACT_SHADOW_WINDOW];
    uint4 tri[VOXR_EXACT_SHADOW_WINDOW];
    for (uint i = 0; i < st->open; ++i) {
      tri[i] = sc->triangles[st->hit_triangle[i]];
      member[i] = i == 0;
    }
    float last = st->hit_t[0];
    for (int changed = 1; changed;) {
      changed = 0;
      for (uint j = 1; j < st->open; ++j) {
        if (member[j]) continue;
        for (uint i = 0; i < st->open && !member[j]; ++i)
          if (member[i] && fabs(st->hit_t[j] - st->hit_t[i]) < sc->merge &&
              tg_shares_vertex(tri[i], tri[j])) {
            member[j] = 1;
            last = fmax(last, st->hit_t[j]);
            changed = 1;
          }
      }
    }
    if (!force && !(bound - last >= sc->merge)) return;
    force = 0;
    /* Its distinct faces and materials. */
    uint4 faces[VOXR_EXACT_SHADOW_GROUP];
    uint materials[VOXR_EXACT_SHADOW_GROUP];
    uint face_count = 0, material_count = 0;
    for (uint i = 0; i < st->open; ++i) {
      if (!member[i]) continue;
      const uint3 key = sx_face_key(tri[i]);
      int seen = 0;
      for (uint f = 0; f < face_count; ++f) seen = seen || all(sx_face_key(faces[f]) == key);
      if (!seen && face_count < VOXR_EXACT_SHADOW_GROUP) faces[face_count++] = tri[i];
      seen = 0;
      for (uint m = 0; m < material_count; ++m) seen = seen || materials[m] == tri[i].w;
      if (!seen && material_count < VOXR_EXACT_SHADOW_GROUP) materials[material_count++] = tri[i].w;
    }
    const float t = st->hit_t[0];
    if (sx_crosses(sc, faces, face_count, st->dir))
      for (uint m = 0; m < material_count; ++m) {
        uint f = 0;
        while (f + 1u < face_count && faces[f].w != materials[m]) ++f;
        sx_event(st, sc, t, materials[m], dot(st->dir, sx_face_normal(sc, faces[f])) < 0.0f);
      }
    /* Keep the others, in order. */
    uint kept = 0;
    for (uint i = 0; i < st->open; ++i)
      if (!member[i]) {
        st->hit_t[kept] = st->hit_t[i];
        st->hit_triangle[kept] = st->hit_triangle[i];
        ++kept;
      }
    st->open = kept;
  }
}

/* Keeps hit (t, triangle), in (t, triangle) order, unless the triangle is kept already (listed in two
 * voxels). */
inline void sx_add(SxState* st, const SxScene* sc, float t, uint triangle) {
  for (uint i = 0; i < st->open; ++i)
    if (st->hit_triangle[i] == triangle) return;
  if (st->open == VOXR_EXACT_SHADOW_WINDOW) sx_close(st, sc, -INFINITY, 1);
  uint i = st->open;
  while (i > 0 && (st->hit_t[i - 1] > t || (st->hit_t[i - 1] == t && st->hit_triangle[i - 1] > triangle))) {
    st->hit_t[i] = st->hit_t[i - 1];
    st->hit_triangle[i] = st->hit_triangle[i - 1];
    --i;
  }
  st->hit_t[i] = t;
  st->hit_triangle[i] = triangle;
  ++st->open;
}

/* The transmittance once every group is closed. */
inline float3 sx_result(const SxState* st, const SxScene* sc) {
  if (st->blocked) return (float3)(0.0f);
  float3 result = st->sheets;
  for (uint s = 0; s < st->solids; ++s) {
    const float length = voxr_ledger_inside_length(&st->solid[s], st->t_end);
    if (length > 0.0f) {
      const RenderMaterial m = sc->materials[min(st->solid[s].material, sc->material_count - 1u)];
      result *= exp(-vload3(0, m.absorption) * length);
    }
  }
  return result;
}

/* The transmittance from p (on triangle `self`) along unit `dir` to the light at distance t_end (INFINITY:
 * directional), the march going on to the grid's exit when the scene has a dielectric. */
inline float3 sx_trace(const TriangleGridView* tg, const SxScene* sc, float3 p, float3 dir, float t_end,
                       uint self, float start, int has_dielectric) {
  SxState st;
  st.dir = dir;
  st.t_end = t_end;
  st.sheets = (float3)(1.0f);
  st.blocked = 0;
  st.solids = 0;
  st.open = 0;
  /* The ray in grid units with the same parameter t (world units along the unit dir). */
  const float3 o =
      (float3)(dot(tg->to_grid[0].xyz, p) + tg->to_grid[0].w, dot(tg->to_grid[1].xyz, p) + tg->to_grid[1].w,
               dot(tg->to_grid[2].xyz, p) + tg->to_grid[2].w);
  const float3 d =
      (float3)(dot(tg->to_grid[0].xyz, dir), dot(tg->to_grid[1].xyz, dir), dot(tg->to_grid[2].xyz, dir));
  const float tolerance = VOXR_EXACT_SHADOW_TOLERANCE / length(d); /* |d| = 1 / the voxel's world size */
  const TgRay ray = tg_ray(p, dir);
  GvRay walk;
  if (gv_ray_begin(&walk, &tg->grid, o, d)) {
    const uint max_steps = 3u * (tg->grid.dims_x + tg->grid.dims_y + tg->grid.dims_z);
    for (uint step = 0; step < max_steps; ++step) {
      const float t_next = fmin(fmin(walk.tx, walk.ty), fmin(walk.tz, walk.t_exit));
      const ulong v = gv_linear(&tg->grid, walk.i, walk.j, walk.k);
      const int occupied = gv_occupied(&tg->grid, v);
      if (!occupied && tg_brick_empty(tg, walk.i, walk.j, walk.k)) {
        /* Nothing is listed in the brick: on past its exit in one step. */
        const int skipped = tg_skip_brick(&walk, &tg->grid, o, d);
        if (skipped == 0) break;
        if (skipped == 2) continue;
      }
      const uint rank = occupied ? gv_rank(&tg->grid, v) : tg->grid.voxels_set;
      if (rank < tg->grid.voxels_set && tg->offsets[rank + 1] <= tg->capacity) {
        for (ulong e = tg->offsets[rank]; e < tg->offsets[rank + 1]; ++e) {
          const uint id = tg->ids[e];
          if (id == self) continue;
          const uint4 tri = sc->triangles[id];
          float t, b1, b2;
          if (tg_intersect(&ray, sc->positions[tri.x].xyz, sc->positions[tri.y].xyz, sc->positions[tri.z].xyz,
                           fmax(start, walk.t - tolerance), t_next + tolerance, &t, &b1, &b2))
            sx_add(&st, sc, t, id);
        }
      }
      /* Later voxels keep hits from t_next - tolerance on. */
      const float bound = t_next - tolerance;
      sx_close(&st, sc, bound, 0);
      if (st.blocked) break;
      /* Past the light only dielectrics' crossings count. */
      if (!has_dielectric && bound >= t_end && (st.open == 0 || st.hit_t[0] >= t_end)) break;
      if (gv_ray_step(&walk, &tg->grid) < 0) break;
    }
  }
  sx_close(&st, sc, INFINITY, 0);
  return sx_result(&st, sc);
}

__kernel __attribute__((reqd_work_group_size(SHADOW_GROUP, 1, 1))) void shadow_exact(
    __global const SurfaceSample* samples, uint count, __global const RenderMaterial* materials,
    uint material_count, RenderLight light, VOXR_TRIANGLE_GRID_PARAMS, float scene_size, uint has_dielectric,
    __global float4* transmittance) {
  const uint id = get_global_id(0);
  if (id >= count) return;
  const SurfaceSample s = samples[id];
  float3 result = (float3)(1.0f);
  if (s.triangle != VOXR_NO_TRIANGLE &&
      materials[min(s.material, material_count - 1u)].kind != VOXR_MATERIAL_DIELECTRIC) {
    const TriangleGridView tg = VOXR_TRIANGLE_GRID();
    const float3 p = vload3(0, s.position);
    float3 dir;
    float t_end;
    if (light.directional) {
      dir = -vload3(0, light.direction);
      t_end = INFINITY;
    } else {
      const float3 to = vload3(0, light.position) - p;
      t_end = length(to);
      dir = to / t_end;
    }
    if (t_end > 0.0f) {
      SxScene sc;
      sc.positions = tg.positions;
      sc.triangles = tg.triangles;
      sc.materials = materials;
      sc.material_count = material_count;
      sc.merge = VOXR_SHADOW_MERGE_DISTANCE * scene_size;
      result = sx_trace(&tg, &sc, p, dir, t_end, s.triangle, VOXR_SHADOW_START_EPSILON * scene_size,
                        has_dielectric != 0);
    }
  }
  transmittance[id] = (float4)(result, 1.0f);
}
