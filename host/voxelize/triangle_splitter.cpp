#include "voxelize/triangle_splitter.h"

#include <algorithm>

#include "voxelize/snapped_triangle.h"

namespace voxr {

namespace {

struct Splitter {
  const std::array<float, 12>& m;
  const GridSpec& grid;
  TriangleSoup& out;

  void split(const glm::vec3 (&w)[3], uint32_t material) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const glm::vec3& p : w) {
      const glm::vec3 g = grid_coords(m, glm::vec4(p, 1.0f));
      lo = glm::min(lo, g);
      hi = glm::max(hi, g);
    }
    for (int a = 0; a < 3; ++a)
      if (hi[a] < -1.0f || lo[a] > float(grid.dims[a]) + 1.0f) return;  // misses the grid
    const glm::vec3 extent = hi - lo;
    if (std::max({extent.x, extent.y, extent.z}) <= kSplitExtentVoxels) {
      const uint32_t base = uint32_t(out.positions.size());
      for (const glm::vec3& p : w) out.positions.push_back(glm::vec4(p, 1.0f));
      out.triangles.push_back({base, base + 1, base + 2, material});
      return;
    }
    const glm::vec3 ab = 0.5f * (w[0] + w[1]), bc = 0.5f * (w[1] + w[2]), ca = 0.5f * (w[2] + w[0]);
    const glm::vec3 pieces[4][3] = {{w[0], ab, ca}, {ab, w[1], bc}, {ca, bc, w[2]}, {ab, bc, ca}};
    for (const auto& piece : pieces) split(piece, material);
  }
};

}  // namespace

std::optional<TriangleSoup> split_oversized_triangles(const TriangleSoup& soup, const GridSpec& grid,
                                                      uint64_t* split) {
  const std::array<float, 12> m = grid.world_to_grid();
  auto oversized = [&](const glm::uvec4& t) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (int c = 0; c < 3; ++c) {
      const glm::vec3 g = grid_coords(m, soup.positions[t[c]]);
      lo = glm::min(lo, g);
      hi = glm::max(hi, g);
    }
    const glm::vec3 e = hi - lo;
    return std::max({e.x, e.y, e.z}) > kSplitExtentVoxels;
  };
  uint64_t count = 0;
  for (const glm::uvec4& t : soup.triangles) count += oversized(t);
  if (split) *split = count;
  if (count == 0) return std::nullopt;

  TriangleSoup out;
  out.positions = soup.positions;
  Splitter splitter{m, grid, out};
  for (const glm::uvec4& t : soup.triangles) {
    if (!oversized(t)) {
      out.triangles.push_back(t);
      continue;
    }
    const glm::vec3 w[3] = {glm::vec3(soup.positions[t.x]), glm::vec3(soup.positions[t.y]),
                            glm::vec3(soup.positions[t.z])};
    splitter.split(w, t.w);
  }
  return out;
}

}  // namespace voxr
