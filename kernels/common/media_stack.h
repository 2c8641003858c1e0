/* media_stack.h — the one rule for which dielectric media a ray is inside, shared by every refraction
 * kernel (refraction_path.h rp_interface), the Embree references (host/reference/reference_refraction.cpp,
 * ReferenceScene::transmittance) and the exact shadows (shadow_exact.cl). C subset that OpenCL C 1.2 and
 * C++20 both accept. docs/methods.md "The media stack" states it.
 *
 * Whether a surface is entered or left is decided by its winding: every closed mesh winds counter-clockwise
 * seen from outside (docs/scene-format.md; the generators and the readers keep the file's winding), so the
 * winding's normal points out of the material. A ray whose direction is against it (dot < 0) enters the
 * material, along it leaves.
 *
 * Paths (VoxrMedia): a stack of entries, innermost last, each a material and a count of nested solids of
 * that material the path is inside.
 *   - Entering m: when the innermost entry is m, its count + 1 (n2 = n1: no interface, so no bend, F = 0 and
 *     no event counted); else a new entry (m, 1), n2 = m's index.
 *   - Leaving m (the innermost entry of m): count > 1: count - 1, n2 = n1; the last of the innermost entry:
 *     the entry goes, n2 is the medium below (air at the bottom); the last of an outer entry (overlapping
 *     solids of different materials): the entry goes, n2 = n1 (the ray stays in the innermost medium).
 *   - Fallback: a surface "left" of a material the path is not inside (an open or inside-out mesh) is
 *     entered, as the parity rule did; one met edge-on (facing 0 or NaN: a voxel normal that cancels) is
 *     left when the path is inside its material and entered when not, as parity did.
 * Shadow rays (VoxrSolidLedger, one per dielectric material met): each crossing is +1 (entered along the
 * ray) or -1 (left); the ray runs to infinity, where it is outside everything, so the depth at the
 * receiver is minus the sum over the whole ray, and a segment is inside where its depth is > 0. A material
 * whose depth would be negative somewhere, or beyond +-VOXR_LEDGER_LEVELS (an open or inside-out mesh), is
 * taken by parity as before: an odd number of crossings over the whole ray means the receiver is inside. */
#ifndef VOXR_MEDIA_STACK_H
#define VOXR_MEDIA_STACK_H

#include "voxr_layout.h"

#ifndef __OPENCL_VERSION__
#include <cmath>
#endif

/* Nested media entries a path holds (deeper nesting ends the path: VOXR_PATH_LOST). */
#define VOXR_MAX_MEDIA 4
/* No medium: the ray is in air (index 1). */
#define VOXR_MEDIA_AIR 0xffffffffu

typedef struct VoxrMedia {
  uint material[VOXR_MAX_MEDIA]; /* innermost last */
  uint count[VOXR_MAX_MEDIA];    /* nested solids of that material, >= 1 */
  uint depth;                    /* entries in use */
} VoxrMedia;

/* A path in air. */
inline VoxrMedia voxr_media_empty(void) {
  VoxrMedia m;
  for (uint k = 0; k < VOXR_MAX_MEDIA; ++k) m.material[k] = m.count[k] = 0u;
  m.depth = 0u;
  return m;
}

/* The innermost medium (whose absorption and index the path has now), or VOXR_MEDIA_AIR. */
inline uint voxr_media_top(const VoxrMedia* m) {
  return m->depth > 0u ? m->material[m->depth - 1u] : VOXR_MEDIA_AIR;
}

/* The innermost entry of material `mat`, or -1. */
inline int voxr_media_find(const VoxrMedia* m, uint mat) {
  int at = -1;
  for (uint k = 0; k < m->depth; ++k)
    if (m->material[k] == mat) at = (int)k;
  return at;
}

/* Whether a surface of material `mat` whose winding normal makes `facing` = dot(ray direction, normal) with
 * the ray is entered (1) or left (0): entered when the path is not inside `mat` (the fallback, whatever the
 * winding) or the normal faces the ray (facing < 0); left otherwise. A surface met edge-on (facing 0, or NaN
 * from a cancelled voxel normal) thus takes parity's choice: left when inside, entered when not. */
inline int voxr_media_enters(const VoxrMedia* m, uint mat, float facing) {
  return voxr_media_find(m, mat) < 0 || facing < 0.0f;
}

/* Whether entering `mat` needs an entry the stack has no room for (the caller ends the path). */
inline int voxr_media_overflows(const VoxrMedia* m, uint mat, int enters) {
  return enters && voxr_media_top(m) != mat && m->depth == VOXR_MAX_MEDIA;
}

/* The medium on the far side of the surface (whose index is n2): `mat` when entering it; when leaving, the
 * innermost medium itself (n2 = n1) unless the last solid of the innermost entry is left, then the entry
 * below it (or VOXR_MEDIA_AIR). */
inline uint voxr_media_far(const VoxrMedia* m, uint mat, int enters) {
  if (enters) return mat;
  const int at = voxr_media_find(m, mat);
  if (at >= 0 && m->count[at] == 1u && (uint)at + 1u == m->depth)
    return at > 0 ? m->material[at - 1] : VOXR_MEDIA_AIR;
  return voxr_media_top(m);
}

/* Crosses the surface (after refracting through it; not on total internal reflection). */
inline void voxr_media_cross(VoxrMedia* m, uint mat, int enters) {
  if (enters) {
    const uint top = m->depth > 0u ? m->depth - 1u : 0u;
    if (m->depth > 0u && m->material[top] == mat) {
      ++m->count[top];
    } else if (m->depth < VOXR_MAX_MEDIA) {
      m->material[m->depth] = mat;
      m->count[m->depth] = 1u;
      ++m->depth;
    }
    return;
  }
  const int at = voxr_media_find(m, mat);
  if (at < 0) return;
  if (--m->count[at] > 0u) return;
  for (uint k = (uint)at; k + 1u < m->depth; ++k) {
    m->material[k] = m->material[k + 1u];
    m->count[k] = m->count[k + 1u];
  }
  --m->depth;
}

/* Shadow rays: relative depths -VOXR_LEDGER_LEVELS .. +VOXR_LEDGER_LEVELS are tracked. */
#define VOXR_LEDGER_LEVELS 4

typedef struct VoxrSolidLedger {
  uint material;
  int level;          /* sum of the crossings' signs so far (+1 entered, -1 left) */
  int level_at_light; /* the sum over the crossings before the light */
  int lowest;         /* the least sum reached (0 at the receiver) */
  int beyond;         /* 1: a sum left the tracked levels */
  uint crossings;     /* over the whole ray (the parity fallback) */
  uint before;        /* before the light */
  float parity_sum;   /* -t1 + t2 - t3 ... of the crossings before the light (the parity fallback) */
  float last_t;       /* the last crossing before the light (0: the receiver) */
  float length[2 * VOXR_LEDGER_LEVELS + 1]; /* length before the light at each sum (index sum + LEVELS) */
} VoxrSolidLedger;

inline VoxrSolidLedger voxr_ledger_make(uint material) {
  VoxrSolidLedger l;
  l.material = material;
  l.level = l.level_at_light = l.lowest = l.beyond = 0;
  l.crossings = l.before = 0u;
  l.parity_sum = l.last_t = 0.0f;
  for (int k = 0; k < 2 * VOXR_LEDGER_LEVELS + 1; ++k) l.length[k] = 0.0f;
  return l;
}

/* One crossing at distance t from the receiver, entering (enters = 1: the winding normal faces the ray)
 * or leaving; before_light: t is before the light. Crossings come in order of t. */
inline void voxr_ledger_cross(VoxrSolidLedger* l, float t, int enters, int before_light) {
  ++l->crossings;
  if (before_light) {
    ++l->before;
    l->parity_sum += (l->before & 1u) ? -t : t;
    if (!l->beyond) l->length[l->level + VOXR_LEDGER_LEVELS] += t - l->last_t;
    l->last_t = t;
  }
  l->level += enters ? 1 : -1;
  if (before_light) l->level_at_light = l->level;
  if (l->level < l->lowest) l->lowest = l->level;
  if (l->level < -VOXR_LEDGER_LEVELS || l->level > VOXR_LEDGER_LEVELS) l->beyond = 1;
}

/* The length of the segment [receiver, light] (t_end; INFINITY: directional) inside the material, once
 * every crossing of the whole ray is in: by winding (depth = sum - total sum > 0) where consistent, else by
 * parity. */
inline float voxr_ledger_inside_length(const VoxrSolidLedger* l, float t_end) {
  const int total = l->level;
  const int finite = t_end < INFINITY;
  if (!l->beyond && l->lowest >= total) {
    float length = 0.0f;
    for (int k = total + 1; k <= VOXR_LEDGER_LEVELS; ++k) length += l->length[k + VOXR_LEDGER_LEVELS];
    if (finite && l->level_at_light > total) length += t_end - l->last_t; /* a point light inside */
    return length;
  }
  const int inside = (int)(l->crossings & 1u); /* at the receiver */
  const int inside_at_light = inside ^ (int)(l->before & 1u);
  float length = inside ? -l->parity_sum : l->parity_sum;
  if (inside_at_light && finite) length += t_end;
  return length;
}

#endif
