/* raster_setup.cl — stage 1 of the kernel rasterizer: per triangle, transform to clip space, drop it when its
 * material kind is not drawn, it faces the culled way (RasterParams.cull) or it lies wholly outside one side
 * of the view, clip it against the near plane (z >= 0) and the guard band in homogeneous space, project and
 * snap the polygon to 1/VOXR_SUBPIXEL pixel, find its depth plane and the tiles of its pixel bounding box,
 * and count them (one raster record each).
 *
 * Clipping computes every intersection from the edge's two endpoints in a canonical order (the
 * lexicographically smaller clip-space point first), so two triangles sharing an edge get bit-identical clip
 * points and their snapped edges still coincide. Only +, -, *, / and rint are used on floats, without
 * contraction, so the host mirror (host/render/reference_raster.cpp) is exact where division is correctly
 * rounded (the runtime asks for it where the device offers it).
 * in:  params, positions (float4), triangles (uint4: indices, material), materials (RenderMaterial)
 * out: prims[t] (vertex_count 0 when not drawn), tile_counts[t], tile_boxes[t] (its tiles: util/expand_copies.cl)
 * shape: one work item per triangle. */
#include "raster_coverage.h"

#ifndef WG_SIZE
#define WG_SIZE 256
#endif

#define RASTER_PLANES 5 /* near, then guard band +x, -x, +y, -y */

/* Signed distance-like value of clip point v to plane k: inside when >= 0. */
inline float raster_plane_value(float4 v, int k, const RasterParams* p) {
  switch (k) {
    case 0:
      return v.z;
    case 1:
      return p->guard[0] * v.w - v.x;
    case 2:
      return p->guard[0] * v.w + v.x;
    case 3:
      return p->guard[1] * v.w - v.y;
    default:
      return p->guard[1] * v.w + v.y;
  }
}

inline int raster_point_less(float4 a, float4 b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  if (a.z != b.z) return a.z < b.z;
  return a.w < b.w;
}

/* The point where segment (a, b) crosses the plane (values da, db of opposite sides), from the canonical end.
 */
inline float4 raster_intersect(float4 a, float da, float4 b, float db) {
  if (raster_point_less(b, a)) {
    const float4 s = a;
    a = b;
    b = s;
    const float ds = da;
    da = db;
    db = ds;
  }
  const float t = da / (da - db);
  return (float4)(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z), a.w + t * (b.w - a.w));
}

/* determinant of the 3x3 matrix with rows a, b, c, in a fixed order. */
inline float raster_det3(float a0, float a1, float a2, float b0, float b1, float b2, float c0, float c1,
                         float c2) {
  return (a0 * (b1 * c2 - b2 * c1) - a1 * (b0 * c2 - b2 * c0)) + a2 * (b0 * c1 - b1 * c0);
}

inline int raster_finite4(float4 v) {
  return isfinite(v.x) && isfinite(v.y) && isfinite(v.z) && isfinite(v.w);
}

inline float4 raster_to_clip(const RasterParams* p, float4 q) {
  const float* m = p->view_projection; /* column-major: m[4 * column + row] */
  float c[4];
  for (int r = 0; r < 4; ++r) c[r] = ((m[r] * q.x + m[4 + r] * q.y) + m[8 + r] * q.z) + m[12 + r];
  return (float4)(c[0], c[1], c[2], c[3]);
}

/* Sets up triangle `t` into prims[t] and its tiles into `box`; returns its tile count (0: not drawn). */
inline uint raster_setup_triangle(const RasterParams* p, __global const float4* positions, uint4 tri,
                                  __global const RenderMaterial* materials, __global RasterPrim* out,
                                  CopyBox* box) {
  if (tri.w >= p->material_count) return 0;
  const uint kind = materials[tri.w].kind;
  if (kind >= 32u || !((p->kind_mask >> kind) & 1u)) return 0;

  float4 c[3];
  c[0] = raster_to_clip(p, positions[tri.x]);
  c[1] = raster_to_clip(p, positions[tri.y]);
  c[2] = raster_to_clip(p, positions[tri.z]);
  if (!raster_finite4(c[0]) || !raster_finite4(c[1]) || !raster_finite4(c[2])) return 0;
  /* Wholly outside one side of the view volume (behind the near plane, beyond far, or off one edge). */
  int outside[6] = {1, 1, 1, 1, 1, 1};
  for (int i = 0; i < 3; ++i) {
    outside[0] &= c[i].z < 0.0f;
    outside[1] &= c[i].z > c[i].w;
    outside[2] &= c[i].x > c[i].w;
    outside[3] &= c[i].x < -c[i].w;
    outside[4] &= c[i].y > c[i].w;
    outside[5] &= c[i].y < -c[i].w;
  }
  for (int k = 0; k < 6; ++k)
    if (outside[k]) return 0;

  /* The plane through the three clip points, L . (x, y, z, w) = 0 (generalized cross product of c0 and the
   * edges), gives z_ndc = -(Lx x_ndc + Ly y_ndc + Lw) / Lz at any screen point of the triangle. */
  const float4 e1 = c[1] - c[0], e2 = c[2] - c[0];
  const float lx = raster_det3(c[0].y, c[0].z, c[0].w, e1.y, e1.z, e1.w, e2.y, e2.z, e2.w);
  const float ly = -raster_det3(c[0].x, c[0].z, c[0].w, e1.x, e1.z, e1.w, e2.x, e2.z, e2.w);
  const float lz = raster_det3(c[0].x, c[0].y, c[0].w, e1.x, e1.y, e1.w, e2.x, e2.y, e2.w);
  const float lw = -raster_det3(c[0].x, c[0].y, c[0].z, e1.x, e1.y, e1.z, e2.x, e2.y, e2.z);
  const float half_w = (float)p->width * 0.5f, half_h = (float)p->height * 0.5f;
  /* x_ndc = (px - W/2) / (W/2), y_ndc = (H/2 - py) / (H/2). */
  const float depth0 = -lx / (lz * half_w), depth1 = ly / (lz * half_h), depth2 = -lw / lz;
  if (!(lz != 0.0f) || !isfinite(depth0) || !isfinite(depth1) || !isfinite(depth2)) return 0;

  /* Sutherland-Hodgman against the near plane and the guard band. */
  float4 poly[VOXR_RASTER_MAX_VERTICES], next[VOXR_RASTER_MAX_VERTICES];
  int n = 3;
  for (int i = 0; i < 3; ++i) poly[i] = c[i];
  for (int k = 0; k < RASTER_PLANES; ++k) {
    float d[VOXR_RASTER_MAX_VERTICES];
    int all_in = 1;
    for (int i = 0; i < n; ++i) {
      d[i] = raster_plane_value(poly[i], k, p);
      all_in &= d[i] >= 0.0f;
    }
    if (all_in) continue;
    int m = 0;
    for (int i = 0; i < n; ++i) {
      const int j = i + 1 < n ? i + 1 : 0;
      const int in_i = d[i] >= 0.0f, in_j = d[j] >= 0.0f;
      if (in_i) {
        if (m == VOXR_RASTER_MAX_VERTICES) return 0;
        next[m++] = poly[i];
      }
      if (in_i != in_j) {
        if (m == VOXR_RASTER_MAX_VERTICES) return 0;
        next[m++] = raster_intersect(poly[i], d[i], poly[j], d[j]);
      }
    }
    if (m < 3) return 0;
    n = m;
    for (int i = 0; i < n; ++i) poly[i] = next[i];
  }

  /* Project and snap; drop repeated points (clip points on a vertex, or closer than the lattice). */
  const float sx = (float)p->width * (0.5f * (float)VOXR_SUBPIXEL);
  const float sy = (float)p->height * (0.5f * (float)VOXR_SUBPIXEL);
  const float limit = 1073741824.0f; /* 2^30: unreachable inside the guard band; keeps conversions defined */
  int px[VOXR_RASTER_MAX_VERTICES], py[VOXR_RASTER_MAX_VERTICES];
  int k = 0;
  for (int i = 0; i < n; ++i) {
    const float w = poly[i].w;
    if (!(w > 0.0f)) return 0; /* only a matrix whose near plane reaches w = 0 gets here */
    const int x = (int)rint(clamp((poly[i].x / w) * sx + sx, -limit, limit));
    const int y = (int)rint(clamp(sy - (poly[i].y / w) * sy, -limit, limit));
    if (k > 0 && x == px[k - 1] && y == py[k - 1]) continue;
    px[k] = x;
    py[k] = y;
    ++k;
  }
  while (k > 1 && px[k - 1] == px[0] && py[k - 1] == py[0]) --k;
  if (k < 3) return 0;
  long area = 0;
  for (int i = 0; i < k; ++i) {
    const int j = i + 1 < k ? i + 1 : 0;
    area += (long)px[i] * py[j] - (long)px[j] * py[i];
  }
  if (area == 0) return 0;
  /* Face culling: area < 0 is a front face (counter-clockwise as the viewer sees it). */
  if (p->cull == VOXR_CULL_FRONT && area < 0) return 0;
  if (p->cull == VOXR_CULL_BACK && area > 0) return 0;

  /* Pixel centres (x + 1/2) S within the bounding box, clamped to the image. */
  long lo_x = px[0], hi_x = px[0], lo_y = py[0], hi_y = py[0];
  for (int i = 1; i < k; ++i) {
    lo_x = min(lo_x, (long)px[i]);
    hi_x = max(hi_x, (long)px[i]);
    lo_y = min(lo_y, (long)py[i]);
    hi_y = max(hi_y, (long)py[i]);
  }
  const long first_x = max(raster_floor_pixel(lo_x - RASTER_S / 2 + RASTER_S - 1), 0L);
  const long last_x = min(raster_floor_pixel(hi_x - RASTER_S / 2), (long)p->width - 1);
  const long first_y = max(raster_floor_pixel(lo_y - RASTER_S / 2 + RASTER_S - 1), 0L);
  const long last_y = min(raster_floor_pixel(hi_y - RASTER_S / 2), (long)p->height - 1);
  if (first_x > last_x || first_y > last_y) return 0;
  const uint tile_x0 = (uint)first_x / RASTER_TILE, tile_y0 = (uint)first_y / RASTER_TILE;
  const uint tiles_x = (uint)last_x / RASTER_TILE - tile_x0 + 1;
  const uint tiles_y = (uint)last_y / RASTER_TILE - tile_y0 + 1;

  /* Positive orientation (rows down); a negative area means counter-clockwise as the viewer sees it. */
  const int reverse = area < 0;
  out->flags = reverse ? 0u : VOXR_PRIM_BACK;
  for (int i = 0; i < k; ++i) {
    const int s = reverse ? k - 1 - i : i;
    out->x[i] = px[s];
    out->y[i] = py[s];
  }
  box->first = VOXR_CELL(tile_x0, tile_y0);
  box->width = tiles_x;
  out->depth[0] = depth0;
  out->depth[1] = depth1;
  out->depth[2] = depth2;
  out->pad = 0;
  out->vertex_count = (uint)k;
  return tiles_x * tiles_y;
}

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void raster_setup(
    RasterParams params, __global const float4* positions, __global const uint4* triangles,
    __global const RenderMaterial* materials, __global RasterPrim* prims, __global uint* tile_counts,
    __global CopyBox* tile_boxes) {
  const uint t = get_global_id(0);
  if (t >= params.triangle_count) return;
  __global RasterPrim* prim = prims + t;
  CopyBox box = {0, 0};
  const uint count = raster_setup_triangle(&params, positions, triangles[t], materials, prim, &box);
  if (count == 0) prim->vertex_count = 0;
  tile_counts[t] = count;
  tile_boxes[t] = box;
}
