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

// A corner's surface colour attributes, interpolated as positions are (midpoints).
struct CornerColor {
  uint32_t rgba = 0xffffffffu;
  glm::vec2 uv{0.0f};
};

// The midpoint of two RGBA8 colours, per channel rounded half up: (a + b + 1) / 2.
uint32_t mid_rgba(uint32_t a, uint32_t b) {
  uint32_t out = 0;
  for (int s = 0; s < 32; s += 8) out |= ((((a >> s) & 255u) + ((b >> s) & 255u) + 1u) >> 1) << s;
  return out;
}

CornerColor mid(const CornerColor& a, const CornerColor& b) {
  return {mid_rgba(a.rgba, b.rgba), 0.5f * (a.uv + b.uv)};
}

struct Splitter {
  const std::array<float, 12>& m;
  const GridSpec& grid;
  SplitCull cull;
  TriangleSoup& out;
  // Which colour arrays the soup has (pieces' new vertices get entries in those) and the triangle's look.
  bool rgba = false, uv = false, looks = false;

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

  void split(glm::vec3 (&w)[3], const CornerColor (&c)[3], uint32_t material, uint32_t look) {
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
      for (int k = 0; k < 3; ++k) {
        if (rgba) out.colors.vertex_rgba.push_back(c[k].rgba);
        if (uv) out.colors.vertex_uv.push_back(c[k].uv);
      }
      out.triangles.push_back({base, base + 1, base + 2, material});
      if (looks) out.colors.triangle_look.push_back(look);
      return;
    }
    const glm::vec3 ab = 0.5f * (w[0] + w[1]), bc = 0.5f * (w[1] + w[2]), ca = 0.5f * (w[2] + w[0]);
    glm::vec3 pieces[4][3] = {{w[0], ab, ca}, {ab, w[1], bc}, {ca, bc, w[2]}, {ab, bc, ca}};
    const CornerColor cab = mid(c[0], c[1]), cbc = mid(c[1], c[2]), cca = mid(c[2], c[0]);
    const CornerColor colors[4][3] = {{c[0], cab, cca}, {cab, c[1], cbc}, {cca, cbc, c[2]}, {cab, cbc, cca}};
    for (int k = 0; k < 4; ++k) split(pieces[k], colors[k], material, look);
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
  // Colours: pieces get their parent's look, and their new vertices the colour and UV interpolated as
  // their positions are.
  const SoupColors& colors = soup.colors;
  out.colors.vertex_rgba = colors.vertex_rgba;
  out.colors.vertex_uv = colors.vertex_uv;
  out.colors.looks = colors.looks;
  out.colors.textures = colors.textures;
  Splitter splitter{m, grid, cull, out};
  // Colour arrays are empty or full length (validate_soup); a shorter one is treated as absent here.
  splitter.rgba = colors.vertex_rgba.size() >= soup.positions.size() && !colors.vertex_rgba.empty();
  splitter.uv = colors.vertex_uv.size() >= soup.positions.size() && !colors.vertex_uv.empty();
  splitter.looks = colors.triangle_look.size() >= soup.triangles.size() && !colors.triangle_look.empty();
  for (size_t i = 0; i < soup.triangles.size(); ++i) {
    const glm::uvec4& t = soup.triangles[i];
    const uint32_t look = splitter.looks ? colors.triangle_look[i] : 0u;
    if (!needs_work(t)) {
      out.triangles.push_back(t);
      if (splitter.looks) out.colors.triangle_look.push_back(look);
      continue;
    }
    glm::vec3 w[3] = {glm::vec3(soup.positions[t.x]), glm::vec3(soup.positions[t.y]),
                      glm::vec3(soup.positions[t.z])};
    CornerColor c[3];
    for (int k = 0; k < 3; ++k) {
      if (splitter.rgba) c[k].rgba = colors.vertex_rgba[t[k]];
      if (splitter.uv) c[k].uv = colors.vertex_uv[t[k]];
    }
    splitter.split(w, c, t.w, look);
  }
  return out;
}

}  // namespace voxr
