/* vox_triangle.h — one triangle in exact grid coordinates, shared by every voxelization kernel (setup,
 * scanline, Grid, slicemap, solid) and mirrored on the host by host/voxelize/snapped_triangle.cpp.
 *
 * Vertices are transformed to grid units in float (no contraction, so the host reproduces them bit for
 * bit) and snapped to the 1/VOXR_SUBVOXEL lattice. Everything after the snap is 64-bit integer arithmetic.
 * Ranges below are inclusive voxel/row/slab index ranges, already clamped to the grid. */
#ifndef VOX_TRIANGLE_H
#define VOX_TRIANGLE_H

#include "voxr_layout.h"

#pragma OPENCL FP_CONTRACT OFF

#define VOX_S ((long)VOXR_SUBVOXEL)

typedef struct VoxTri {
  long v[3][3];   /* snapped vertices, fixed point */
  long lo[3];     /* bounding box, fixed point */
  long hi[3];
  long n[3];      /* (v1-v0) x (v2-v0), fixed point squared */
  int first[3];   /* first voxel index along x, y, z touched under the raster rule */
  int last[3];    /* last index; first > last when the triangle misses the grid */
} VoxTri;

/* floor(a / VOXR_SUBVOXEL) with shifts of non-negative values only (no 64-bit division, and no reliance
 * on how >> treats negative numbers): for a < 0, floor(a/S) = ~(~a >> bits). */
inline long vox_floor_cell(long a) {
  return a >= 0 ? a >> VOXR_SUBVOXEL_BITS : ~((~a) >> VOXR_SUBVOXEL_BITS);
}

/* Round half to even, as rint (and the host's std::nearbyint). Below 2^22 in magnitude by adding and
 * removing 1.5 * 2^23, which leaves an integer under float's default rounding: PoCL's library rint is a
 * long branchy sequence, and this snap runs nine times per triangle. */
inline long vox_rint(float g) {
  if (fabs(g) < 4194304.0f) {
    const float magic = 12582912.0f;
    return (long)((g + magic) - magic);
  }
  return (long)rint(g);
}

inline long vox_snap(float g) {
  /* Clamp far-away coordinates so the conversion is defined; such triangles never reach the grid. */
  const float limit = 1.0e9f;
  return vox_rint(clamp(g * (float)VOXR_SUBVOXEL, -limit, limit)); /* integral: the conversion is exact */
}

/* Transforms and snaps the triangle's vertices (vox_setup.cl stores them for the later stages). */
inline void vox_snap_triangle(VoxTri* t, const VoxGridParams* grid, __global const float4* positions, uint4 tri) {
  const float4 p[3] = {positions[tri.x], positions[tri.y], positions[tri.z]};
  for (int c = 0; c < 3; ++c) {
    for (int a = 0; a < 3; ++a) {
      /* Explicit evaluation order; the host mirrors it. */
      const float* m = grid->world_to_grid + 4 * a;
      t->v[c][a] = vox_snap(((m[0] * p[c].x + m[1] * p[c].y) + m[2] * p[c].z) + m[3]);
    }
    t->v[c][2] -= (long)grid->first_slice * VOXR_SUBVOXEL; /* a window's slices (VoxGridParams.first_slice) */
  }
}

/* Stored form (voxr_layout.h VoxSnappedTriangle); |coordinates| < 2^31 after the snap's clamp. */
inline void vox_store_triangle(const VoxTri* t, uint material, __global VoxSnappedTriangle* snapped, uint index) {
  __global VoxSnappedTriangle* out = snapped + index;
  for (int c = 0; c < 3; ++c) {
    out->x[c] = (int)t->v[c][0];
    out->y[c] = (int)t->v[c][1];
    out->z[c] = (int)t->v[c][2];
  }
  out->material = material;
}

inline uint vox_fetch_triangle(VoxTri* t, __global const VoxSnappedTriangle* snapped, uint index) {
  __global const VoxSnappedTriangle* in = snapped + index;
  for (int c = 0; c < 3; ++c) {
    t->v[c][0] = in->x[c];
    t->v[c][1] = in->y[c];
    t->v[c][2] = in->z[c];
  }
  return in->material;
}

/* Bounding box, normal and the index ranges of snapped vertices. */
inline void vox_derive(VoxTri* t, const VoxGridParams* grid) {
  for (int a = 0; a < 3; ++a) {
    t->lo[a] = min(t->v[0][a], min(t->v[1][a], t->v[2][a]));
    t->hi[a] = max(t->v[0][a], max(t->v[1][a], t->v[2][a]));
  }
  const long e0[3] = {t->v[1][0] - t->v[0][0], t->v[1][1] - t->v[0][1], t->v[1][2] - t->v[0][2]};
  const long e1[3] = {t->v[2][0] - t->v[0][0], t->v[2][1] - t->v[0][1], t->v[2][2] - t->v[0][2]};
  t->n[0] = e0[1] * e1[2] - e0[2] * e1[1];
  t->n[1] = e0[2] * e1[0] - e0[0] * e1[2];
  t->n[2] = e0[0] * e1[1] - e0[1] * e1[0];

  for (int a = 0; a < 3; ++a) {
    long first, last;
#if VOXR_MODE == VOXR_MODE_CONSERVATIVE
    /* Closed boxes widened by the margin, [k*S - m, (k+1)*S + m]: k*S - m <= hi and (k+1)*S + m >= lo. */
    const long m = (long)grid->margin;
    first = vox_floor_cell(t->lo[a] - m - 1);
    last = vox_floor_cell(t->hi[a] + m);
#else
    if (a < 2) { /* pixel centres (j + 1/2) * S inside [lo, hi] */
      first = vox_floor_cell(t->lo[a] - VOX_S / 2 + VOX_S - 1);
      last = vox_floor_cell(t->hi[a] - VOX_S / 2);
    } else { /* half-open slabs [k*S, (k+1)*S) containing a depth in [lo, hi] */
      first = vox_floor_cell(t->lo[a]);
      last = vox_floor_cell(t->hi[a]);
    }
#endif
    t->first[a] = (int)max(first, 0L);
    t->last[a] = (int)min(last, (long)grid->dims[a] - 1);
  }
}

/* The setup stages' common start: snap triangle t, derive its ranges and store it for the later stages. */
inline void vox_prepare_triangle(VoxTri* t, const VoxGridParams* grid, __global const float4* positions,
                                 uint4 indices, __global VoxSnappedTriangle* snapped, uint index) {
  vox_snap_triangle(t, grid, positions, indices);
  vox_derive(t, grid);
  vox_store_triangle(t, indices.w, snapped, index);
}

/* Whether the triangle produces any copy: it reaches the grid and, for the centre rule, its projection
 * on the slicing plane has area (an edge-on triangle covers no pixel centre). */
inline int vox_triangle_active(const VoxTri* t) {
  int active = t->first[0] <= t->last[0] && t->first[1] <= t->last[1] && t->first[2] <= t->last[2];
#if VOXR_MODE == VOXR_MODE_CENTER
  active = active && t->n[2] != 0;
#endif
  return active;
}

inline int vox_triangle_too_large(const VoxTri* t) {
  const long limit = (long)VOXR_MAX_TRIANGLE_EXTENT * VOX_S;
  return t->hi[0] - t->lo[0] > limit || t->hi[1] - t->lo[1] > limit || t->hi[2] - t->lo[2] > limit;
}

inline uint vox_row_blocks(const VoxTri* t, uint rows_per_copy) {
  return (uint)(t->last[1] - t->first[1]) / rows_per_copy + 1;
}

/* The centre rule's coverage of column centres ((i+1/2) S, (j+1/2) S) by the triangle's projection on the
 * slicing plane: edge functions of the projected edges in counter-clockwise order, with the top-left rule's
 * bias so that a centre on an edge shared by two triangles belongs to exactly one of them. Shared by every
 * kernel that samples column centres (vox_scanline.h's centre mode, slicemap_raster.cl, vox_solid_cross.cl). */
typedef struct VoxCoverage {
  long px[3], py[3]; /* projected vertices, counter-clockwise */
  long dx[3], dy[3]; /* edge e runs from vertex e to vertex e+1 */
  long bias[3];      /* 0 for top and left edges: a centre exactly on them is inside */
} VoxCoverage;

inline void vox_coverage_init(VoxCoverage* c, const VoxTri* t) {
  const int o1 = t->n[2] > 0 ? 1 : 2, o2 = t->n[2] > 0 ? 2 : 1;
  const int order[3] = {0, o1, o2};
  for (int e = 0; e < 3; ++e) {
    c->px[e] = t->v[order[e]][0];
    c->py[e] = t->v[order[e]][1];
  }
  for (int e = 0; e < 3; ++e) {
    const int f = e == 2 ? 0 : e + 1;
    c->dx[e] = c->px[f] - c->px[e];
    c->dy[e] = c->py[f] - c->py[e];
    c->bias[e] = (c->dy[e] < 0 || (c->dy[e] == 0 && c->dx[e] < 0)) ? 0 : 1;
  }
}

/* Edge functions at the centre of column (i, j). */
inline void vox_coverage_start(const VoxCoverage* c, int i, int j, long edge[3]) {
  const long cx = (long)i * VOX_S + VOX_S / 2, cy = (long)j * VOX_S + VOX_S / 2;
  for (int e = 0; e < 3; ++e) edge[e] = c->dx[e] * (cy - c->py[e]) - c->dy[e] * (cx - c->px[e]);
}

/* Whether the current centre is covered; then moves the edge functions one column along +x. */
inline int vox_coverage_next(const VoxCoverage* c, long edge[3]) {
  int inside = 1;
  for (int e = 0; e < 3; ++e) {
    inside &= edge[e] >= c->bias[e];
    edge[e] -= c->dy[e] * VOX_S;
  }
  return inside;
}

#endif
