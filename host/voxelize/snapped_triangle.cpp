#include "voxelize/snapped_triangle.h"

#include <algorithm>
#include <cmath>

namespace voxr {

uint32_t snap_margin(const GridSpec& grid, const Bounds& mesh_bounds) {
  const std::array<float, 12> m = grid.world_to_grid();
  Bounds bounds = mesh_bounds;
  for (int c = 0; c < 8; ++c)
    bounds.extend(grid.origin + grid.axes * (glm::vec3(c & 1 ? grid.dims.x : 0u, c & 2 ? grid.dims.y : 0u,
                                                       c & 4 ? grid.dims.z : 0u) *
                                             grid.voxel_size));
  double worst = 0.0;
  for (int a = 0; a < 3; ++a) {
    const float* r = m.data() + 4 * a;
    // The largest |m_c p_c| summed over the box's corners, and the translation's own size.
    double terms = 0.0;
    for (int c = 0; c < 3; ++c)
      terms += std::max(std::abs(double(r[c]) * bounds.lo[c]), std::abs(double(r[c]) * bounds.hi[c])) +
               std::abs(double(r[c]) * grid.origin[c]);
    worst = std::max(worst, terms + std::abs(double(r[3])));
  }
  const double units = 0.5 + worst * std::ldexp(1.0, -20) * VOXR_SUBVOXEL;
  if (!(units < double(1u << 30))) return 1u << 30;
  return std::max<uint32_t>(1, uint32_t(std::ceil(units)));
}

glm::vec3 grid_coords(const std::array<float, 12>& m, const glm::vec4& p) {
  glm::vec3 g;
  for (int a = 0; a < 3; ++a) {
    const float* r = m.data() + 4 * a;
    g[a] = ((r[0] * p.x + r[1] * p.y) + r[2] * p.z) + r[3];
  }
  return g;
}

SnappedTriangle snap_triangle(const std::array<float, 12>& world_to_grid, const TriangleSoup& soup,
                              size_t triangle) {
  const glm::uvec4& tri = soup.triangles[triangle];
  SnappedTriangle t;
  t.material = tri.w;
  for (int c = 0; c < 3; ++c) {
    const glm::vec3 g = grid_coords(world_to_grid, soup.positions[tri[c]]);
    for (int a = 0; a < 3; ++a) {
      const float limit = 1.0e9f;
      const float scaled = std::clamp(g[a] * float(VOXR_SUBVOXEL), -limit, limit);
      t.v[c][a] = int64_t(std::nearbyint(scaled));  // round half to even, like convert_int_rte
    }
  }
  int64_t e0[3], e1[3];
  for (int a = 0; a < 3; ++a) {
    e0[a] = t.v[1][a] - t.v[0][a];
    e1[a] = t.v[2][a] - t.v[0][a];
  }
  t.n = {e0[1] * e1[2] - e0[2] * e1[1], e0[2] * e1[0] - e0[0] * e1[2], e0[0] * e1[1] - e0[1] * e1[0]};
  return t;
}

std::array<int32_t, 3> fixed_normal(const SnappedTriangle& t) {
  const float f[3] = {float(t.n[0]), float(t.n[1]), float(t.n[2])};
  const float len2 = (f[0] * f[0] + f[1] * f[1]) + f[2] * f[2];
  const float scale = len2 > 0.0f ? float(VOXR_NORMAL_ONE) / std::sqrt(len2) : 0.0f;
  std::array<int32_t, 3> out;
  for (int q = 0; q < 3; ++q) out[q] = int32_t(std::nearbyint(f[q] * scale));
  return out;
}

}  // namespace voxr
