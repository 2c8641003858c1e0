#include "voxelize/triangle_splitter.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "voxelize/snapped_triangle.h"

namespace voxr {

namespace {

struct GridBox {
  glm::vec3 lo{std::numeric_limits<float>::max()}, hi{-std::numeric_limits<float>::max()};
};

struct Splitter {
  const std::array<float, 12>& m;
  const GridSpec& grid;
  SplitCull cull;
  TriangleSoup& out;

  GridBox box(const glm::vec3 (&w)[3]) const {
    GridBox b;
    for (const glm::vec3& p : w) {
      const glm::vec3 g = grid_coords(m, glm::vec4(p, 1.0f));
      b.lo = glm::min(b.lo, g);
      b.hi = glm::max(b.hi, g);
    }
    return b;
  }

  // Moves a piece wholly below or above the grid onto a plane half a voxel outside it: its column
  // crossings (all solid fill needs of it) stay, its depth no longer strains the integer predicates.
  void flatten_outside_depth(glm::vec3 (&w)[3], const GridBox& b) const {
    const float nz = float(grid.dims.z);
    const float target = b.hi.z < -1.0f ? -0.5f : b.lo.z > nz + 1.0f ? nz + 0.5f : 0.0f;
    if (target == 0.0f) return;
    const glm::vec3 axis = grid.axes[2] * grid.voxel_size;
    for (glm::vec3& p : w) p += axis * (target - grid_coords(m, glm::vec4(p, 1.0f)).z);
  }

  void split(glm::vec3 (&w)[3], uint32_t material) {
    GridBox b = box(w);
    const int culled_axes = cull == SplitCull::kGrid ? 3 : 2;
    for (int a = 0; a < culled_axes; ++a)
      if (b.hi[a] < -1.0f || b.lo[a] > float(grid.dims[a]) + 1.0f) return;  // misses the grid
    if (cull == SplitCull::kColumns) {
      flatten_outside_depth(w, b);
      b = box(w);
    }
    const glm::vec3 extent = b.hi - b.lo;
    if (std::max({extent.x, extent.y, extent.z}) <= kSplitExtentVoxels) {
      const uint32_t base = uint32_t(out.positions.size());
      for (const glm::vec3& p : w) out.positions.push_back(glm::vec4(p, 1.0f));
      out.triangles.push_back({base, base + 1, base + 2, material});
      return;
    }
    const glm::vec3 ab = 0.5f * (w[0] + w[1]), bc = 0.5f * (w[1] + w[2]), ca = 0.5f * (w[2] + w[0]);
    glm::vec3 pieces[4][3] = {{w[0], ab, ca}, {ab, w[1], bc}, {ca, bc, w[2]}, {ab, bc, ca}};
    for (auto& piece : pieces) split(piece, material);
  }
};

// True when no triangle can need work: every vertex, transformed once, lies in a box no larger than
// kSplitExtentVoxels (a triangle's extent, computed from the same floats, is then no larger: rounding is
// monotonic) and, for kColumns, within a voxel of the grid in depth. NaN coordinates decide nothing here.
bool nothing_to_split(const TriangleSoup& soup, const std::array<float, 12>& m, float nz, SplitCull cull) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  bool nan = false;
  for (const glm::vec4& p : soup.positions) {
    const glm::vec3 g = grid_coords(m, p);
    nan |= std::isnan(g.x) | std::isnan(g.y) | std::isnan(g.z);
    lo = glm::min(lo, g);
    hi = glm::max(hi, g);
  }
  const glm::vec3 e = hi - lo;
  return !nan && e.x <= kSplitExtentVoxels && e.y <= kSplitExtentVoxels && e.z <= kSplitExtentVoxels &&
         (cull != SplitCull::kColumns || (lo.z >= -1.0f && hi.z <= nz + 1.0f));
}

}  // namespace

std::optional<TriangleSoup> split_oversized_triangles(const TriangleSoup& soup, const GridSpec& grid,
                                                      uint64_t* split, SplitCull cull) {
  const std::array<float, 12> m = grid.world_to_grid();
  const float nz = float(grid.dims.z);
  if (nothing_to_split(soup, m, nz, cull)) {
    if (split) *split = 0;
    return std::nullopt;
  }
  auto needs_work = [&](const glm::uvec4& t) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (int c = 0; c < 3; ++c) {
      const glm::vec3 g = grid_coords(m, soup.positions[t[c]]);
      lo = glm::min(lo, g);
      hi = glm::max(hi, g);
    }
    const glm::vec3 e = hi - lo;
    const bool far_in_depth = cull == SplitCull::kColumns && (hi.z < -1.0f || lo.z > nz + 1.0f);
    return std::max({e.x, e.y, e.z}) > kSplitExtentVoxels || far_in_depth;
  };
  uint64_t count = 0;
  for (const glm::uvec4& t : soup.triangles) count += needs_work(t);
  if (split) *split = count;
  if (count == 0) return std::nullopt;

  TriangleSoup out;
  out.positions = soup.positions;
  Splitter splitter{m, grid, cull, out};
  for (const glm::uvec4& t : soup.triangles) {
    if (!needs_work(t)) {
      out.triangles.push_back(t);
      continue;
    }
    glm::vec3 w[3] = {glm::vec3(soup.positions[t.x]), glm::vec3(soup.positions[t.y]),
                      glm::vec3(soup.positions[t.z])};
    splitter.split(w, t.w);
  }
  return out;
}

}  // namespace voxr
