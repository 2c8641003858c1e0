#include "render/reference_raster.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

namespace voxr {

namespace {

constexpr int64_t kS = VOXR_SUBPIXEL;
constexpr int kMax = VOXR_RASTER_MAX_VERTICES;

using Clip = std::array<float, 4>;  // x, y, z, w

float plane_value(const Clip& v, int k, const RasterParams& p) {
  switch (k) {
    case 0:
      return v[2];
    case 1:
      return p.guard[0] * v[3] - v[0];
    case 2:
      return p.guard[0] * v[3] + v[0];
    case 3:
      return p.guard[1] * v[3] - v[1];
    default:
      return p.guard[1] * v[3] + v[1];
  }
}

bool point_less(const Clip& a, const Clip& b) {
  for (int i = 0; i < 3; ++i)
    if (a[i] != b[i]) return a[i] < b[i];
  return a[3] < b[3];
}

Clip intersect(Clip a, float da, Clip b, float db) {
  if (point_less(b, a)) {
    std::swap(a, b);
    std::swap(da, db);
  }
  const float t = da / (da - db);
  Clip r;
  for (int i = 0; i < 4; ++i) r[i] = a[i] + t * (b[i] - a[i]);
  return r;
}

float det3(float a0, float a1, float a2, float b0, float b1, float b2, float c0, float c1, float c2) {
  return (a0 * (b1 * c2 - b2 * c1) - a1 * (b0 * c2 - b2 * c0)) + a2 * (b0 * c1 - b1 * c0);
}

int64_t floor_pixel(int64_t a) {
  return a >= 0 ? a / kS : -((-a + kS - 1) / kS);
}

}  // namespace

uint32_t reference_raster_prim(const TriangleSoup& soup, uint32_t t, const RasterParams& p,
                               const std::vector<RenderMaterial>& materials, RasterPrim& prim) {
  prim = RasterPrim{};
  const glm::uvec4 tri = soup.triangles[t];
  if (tri.w >= p.material_count || tri.w >= materials.size()) return 0;
  const uint32_t kind = materials[tri.w].kind;
  if (kind >= 32 || !((p.kind_mask >> kind) & 1u)) return 0;

  std::array<Clip, 3> c;
  for (int i = 0; i < 3; ++i) {
    const glm::vec4 q = soup.positions[tri[i]];
    for (int r = 0; r < 4; ++r) {
      const float* m = p.view_projection;
      c[i][r] = ((m[r] * q.x + m[4 + r] * q.y) + m[8 + r] * q.z) + m[12 + r];
      if (!std::isfinite(c[i][r])) return 0;
    }
  }
  // Wholly outside one side of the view volume.
  bool outside[6] = {true, true, true, true, true, true};
  for (const Clip& v : c) {
    outside[0] &= v[2] < 0.0f;
    outside[1] &= v[2] > v[3];
    outside[2] &= v[0] > v[3];
    outside[3] &= v[0] < -v[3];
    outside[4] &= v[1] > v[3];
    outside[5] &= v[1] < -v[3];
  }
  for (bool o : outside)
    if (o) return 0;

  // Depth plane: L . (x, y, z, w) = 0 through the three clip points.
  Clip e1, e2;
  for (int i = 0; i < 4; ++i) {
    e1[i] = c[1][i] - c[0][i];
    e2[i] = c[2][i] - c[0][i];
  }
  const Clip& c0 = c[0];
  const float lx = det3(c0[1], c0[2], c0[3], e1[1], e1[2], e1[3], e2[1], e2[2], e2[3]);
  const float ly = -det3(c0[0], c0[2], c0[3], e1[0], e1[2], e1[3], e2[0], e2[2], e2[3]);
  const float lz = det3(c0[0], c0[1], c0[3], e1[0], e1[1], e1[3], e2[0], e2[1], e2[3]);
  const float lw = -det3(c0[0], c0[1], c0[2], e1[0], e1[1], e1[2], e2[0], e2[1], e2[2]);
  const float half_w = float(p.width) * 0.5f, half_h = float(p.height) * 0.5f;
  const float depth0 = -lx / (lz * half_w), depth1 = ly / (lz * half_h), depth2 = -lw / lz;
  if (!(lz != 0.0f) || !std::isfinite(depth0) || !std::isfinite(depth1) || !std::isfinite(depth2)) return 0;

  // Clip against the near plane and the guard band.
  std::vector<Clip> poly(c.begin(), c.end());
  for (int k = 0; k < 5; ++k) {
    std::vector<float> d(poly.size());
    bool all_in = true;
    for (size_t i = 0; i < poly.size(); ++i) {
      d[i] = plane_value(poly[i], k, p);
      all_in &= d[i] >= 0.0f;
    }
    if (all_in) continue;
    std::vector<Clip> next;
    for (size_t i = 0; i < poly.size(); ++i) {
      const size_t j = (i + 1) % poly.size();
      const bool in_i = d[i] >= 0.0f, in_j = d[j] >= 0.0f;
      if (in_i) next.push_back(poly[i]);
      if (in_i != in_j) next.push_back(intersect(poly[i], d[i], poly[j], d[j]));
    }
    if (next.size() > size_t(kMax) || next.size() < 3) return 0;
    poly = std::move(next);
  }

  // Project, snap, drop repeats.
  const float sx = float(p.width) * (0.5f * float(VOXR_SUBPIXEL));
  const float sy = float(p.height) * (0.5f * float(VOXR_SUBPIXEL));
  const float limit = 1073741824.0f;
  std::vector<glm::i64vec2> v;
  for (const Clip& q : poly) {
    const float w = q[3];
    if (!(w > 0.0f)) return 0;
    const int64_t x = int64_t(std::nearbyint(std::clamp((q[0] / w) * sx + sx, -limit, limit)));
    const int64_t y = int64_t(std::nearbyint(std::clamp(sy - (q[1] / w) * sy, -limit, limit)));
    if (!v.empty() && v.back() == glm::i64vec2(x, y)) continue;
    v.push_back({x, y});
  }
  while (v.size() > 1 && v.back() == v.front()) v.pop_back();
  if (v.size() < 3) return 0;
  int64_t area = 0;
  for (size_t i = 0; i < v.size(); ++i) {
    const glm::i64vec2 a = v[i], b = v[(i + 1) % v.size()];
    area += a.x * b.y - b.x * a.y;
  }
  if (area == 0) return 0;
  if (p.cull == VOXR_CULL_FRONT && area < 0) return 0;  // a front face
  if (p.cull == VOXR_CULL_BACK && area > 0) return 0;   // a back face

  int64_t lo_x = v[0].x, hi_x = v[0].x, lo_y = v[0].y, hi_y = v[0].y;
  for (const glm::i64vec2& q : v) {
    lo_x = std::min(lo_x, q.x);
    hi_x = std::max(hi_x, q.x);
    lo_y = std::min(lo_y, q.y);
    hi_y = std::max(hi_y, q.y);
  }
  // Pixel centres (i + 1/2) S within [lo, hi], clamped to the image.
  const int64_t first_x = std::max<int64_t>(floor_pixel(lo_x - kS / 2 + kS - 1), 0);
  const int64_t last_x = std::min<int64_t>(floor_pixel(hi_x - kS / 2), int64_t(p.width) - 1);
  const int64_t first_y = std::max<int64_t>(floor_pixel(lo_y - kS / 2 + kS - 1), 0);
  const int64_t last_y = std::min<int64_t>(floor_pixel(hi_y - kS / 2), int64_t(p.height) - 1);
  if (first_x > last_x || first_y > last_y) return 0;
  const uint32_t tx0 = uint32_t(first_x) / VOXR_RASTER_TILE, ty0 = uint32_t(first_y) / VOXR_RASTER_TILE;
  const uint32_t tiles_x = uint32_t(last_x) / VOXR_RASTER_TILE - tx0 + 1;
  const uint32_t tiles_y = uint32_t(last_y) / VOXR_RASTER_TILE - ty0 + 1;

  if (area < 0) std::reverse(v.begin(), v.end());
  prim.vertex_count = uint32_t(v.size());
  prim.flags = area < 0 ? 0u : VOXR_PRIM_BACK;
  for (size_t i = 0; i < v.size(); ++i) {
    prim.x[i] = int32_t(v[i].x);
    prim.y[i] = int32_t(v[i].y);
  }
  prim.depth[0] = depth0;
  prim.depth[1] = depth1;
  prim.depth[2] = depth2;
  return tiles_x * tiles_y;
}

bool reference_covers(const RasterPrim& prim, uint32_t x, uint32_t y) {
  const int n = int(prim.vertex_count);
  if (n < 3) return false;
  const int64_t cx = int64_t(x) * kS + kS / 2, cy = int64_t(y) * kS + kS / 2;
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    const int64_t dx = int64_t(prim.x[j]) - prim.x[i], dy = int64_t(prim.y[j]) - prim.y[i];
    const int64_t e = dx * (cy - prim.y[i]) - dy * (cx - prim.x[i]);
    const bool top_left = dy < 0 || (dy == 0 && dx > 0);
    if (top_left ? e < 0 : e <= 0) return false;
  }
  return true;
}

float reference_depth(const RasterPrim& prim, uint32_t x, uint32_t y, uint32_t width, uint32_t height) {
  const float dx = (float(x) + 0.5f) - float(width) * 0.5f;
  const float dy = (float(y) + 0.5f) - float(height) * 0.5f;
  const float z = (prim.depth[0] * dx + prim.depth[1] * dy) + prim.depth[2];
  const float above = z > 0.0f ? z : 0.0f;
  return above < 1.0f ? above : 1.0f;
}

ReferenceRaster reference_raster(const TriangleSoup& soup, const RasterTarget& target,
                                 const std::vector<RenderMaterial>& materials) {
  const RasterParams params =
      make_raster_params(target, uint32_t(soup.triangle_count()), uint32_t(materials.size()));
  const uint32_t w = target.width, h = target.height;
  ReferenceRaster out;
  out.visibility.assign(size_t(w) * h, ~uint64_t(0));
  out.counts.assign(size_t(w) * h * 2, 0);
  for (uint32_t t = 0; t < soup.triangle_count(); ++t) {
    RasterPrim prim;
    out.records += reference_raster_prim(soup, t, params, materials, prim);
    if (prim.vertex_count == 0) continue;
    int64_t lo_x = prim.x[0], hi_x = lo_x, lo_y = prim.y[0], hi_y = lo_y;
    for (uint32_t i = 1; i < prim.vertex_count; ++i) {
      lo_x = std::min<int64_t>(lo_x, prim.x[i]);
      hi_x = std::max<int64_t>(hi_x, prim.x[i]);
      lo_y = std::min<int64_t>(lo_y, prim.y[i]);
      hi_y = std::max<int64_t>(hi_y, prim.y[i]);
    }
    const uint32_t x0 = uint32_t(std::clamp<int64_t>(floor_pixel(lo_x), 0, w - 1));
    const uint32_t x1 = uint32_t(std::clamp<int64_t>(floor_pixel(hi_x), 0, w - 1));
    const uint32_t y0 = uint32_t(std::clamp<int64_t>(floor_pixel(lo_y), 0, h - 1));
    const uint32_t y1 = uint32_t(std::clamp<int64_t>(floor_pixel(hi_y), 0, h - 1));
    for (uint32_t y = y0; y <= y1; ++y)
      for (uint32_t x = x0; x <= x1; ++x) {
        if (!reference_covers(prim, x, y)) continue;
        const size_t pixel = size_t(y) * w + x;
        const uint64_t word =
            (uint64_t(std::bit_cast<uint32_t>(reference_depth(prim, x, y, w, h))) << 32) | t;
        out.visibility[pixel] = std::min(out.visibility[pixel], word);
        ++out.counts[2 * pixel + ((prim.flags & VOXR_PRIM_BACK) ? 1 : 0)];
      }
  }
  return out;
}

}  // namespace voxr
