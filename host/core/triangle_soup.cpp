#include "core/triangle_soup.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "util/error.h"

namespace voxr {

namespace {

// A position's four floats as one vector (GCC/Clang vector extension), so that the three axes of a min, max
// or difference are one instruction; element-wise, the operations are the scalar ones.
using Float4 = float __attribute__((vector_size(16)));
static_assert(sizeof(glm::vec4) == sizeof(Float4));
Float4 load(const glm::vec4& p) {
  Float4 v;
  std::memcpy(&v, &p, sizeof v);
  return v;
}

// Corners are gathered from all over `positions`; asking for those of a triangle further on keeps more loads
// in flight (validate_soup on 1.1 M triangles of a subdivided mesh, caches cold: 18 -> 8 ms).
constexpr size_t kPrefetchAhead = 16;
void prefetch_corners(const TriangleSoup& soup, size_t triangle) {
  if (triangle >= soup.triangles.size()) return;
  const glm::uvec4& t = soup.triangles[triangle];
  for (int c = 0; c < 3; ++c)
    if (t[c] < soup.positions.size()) __builtin_prefetch(&soup.positions[t[c]]);
}

}  // namespace

Bounds TriangleSoup::bounds() const {
  // Bounds::extend for every corner in triangle order: the same comparisons in the same order per axis.
  const float big = std::numeric_limits<float>::max();
  Float4 lo = {big, big, big, big}, hi = -lo;
  const glm::vec4* pos = positions.data();
  for (size_t i = 0; i < triangles.size(); ++i) {
    prefetch_corners(*this, i + kPrefetchAhead);
    const glm::uvec4& t = triangles[i];
    for (int c = 0; c < 3; ++c) {
      const Float4 p = load(pos[t[c]]);
      lo = p < lo ? p : lo;  // glm::min(lo, p)
      hi = hi < p ? p : hi;  // glm::max(hi, p)
    }
  }
  Bounds b;
  b.lo = glm::vec3(lo[0], lo[1], lo[2]);
  b.hi = glm::vec3(hi[0], hi[1], hi[2]);
  return b;
}

glm::dvec3 choose_anchor(const glm::dvec3& lo, const glm::dvec3& hi) {
  const glm::dvec3 size = glm::max(hi - lo, glm::dvec3(0.0));
  const double longest = std::max({size.x, size.y, size.z});
  const double scale = longest > 0.0 ? std::exp2(std::ceil(std::log2(longest))) : 1.0;
  return glm::floor(lo / scale) * scale;
}

namespace {

// Appends `b`'s colours (for b_vertices vertices and b_triangles triangles) to `a`'s (for a_vertices and
// a_triangles): an array one side lacks is filled with its default (white, UV (0, 0), a white look), look
// and texture indices of `b` are offset past `a`'s, and a texture of `b` that `a` already holds (same source
// and size) is shared. Nothing happens, and nothing is allocated, when neither has colours.
void append_colors(SoupColors& a, size_t a_vertices, size_t a_triangles, const SoupColors& b,
                   size_t b_vertices, size_t b_triangles) {
  if (a.empty() && b.empty()) return;
  constexpr uint32_t kWhite = 0xffffffffu;
  if (!a.vertex_rgba.empty() || !b.vertex_rgba.empty()) {
    a.vertex_rgba.resize(a_vertices, kWhite);  // fills a soup that had none
    if (b.vertex_rgba.empty())
      a.vertex_rgba.resize(a_vertices + b_vertices, kWhite);
    else
      a.vertex_rgba.insert(a.vertex_rgba.end(), b.vertex_rgba.begin(), b.vertex_rgba.end());
  }
  if (!a.vertex_uv.empty() || !b.vertex_uv.empty()) {
    a.vertex_uv.resize(a_vertices, glm::vec2(0.0f));
    if (b.vertex_uv.empty())
      a.vertex_uv.resize(a_vertices + b_vertices, glm::vec2(0.0f));
    else
      a.vertex_uv.insert(a.vertex_uv.end(), b.vertex_uv.begin(), b.vertex_uv.end());
  }
  if (a.looks.empty() && b.looks.empty()) return;
  // Both sides as explicit per-triangle looks.
  if (a.looks.empty()) a.looks.push_back(SurfaceLook());
  a.triangle_look.resize(a_triangles, 0u);  // no triangle_look: look 0 for every triangle
  const uint32_t look_base = uint32_t(a.looks.size());
  if (b.looks.empty()) {
    a.looks.push_back(SurfaceLook());
    a.triangle_look.resize(a_triangles + b_triangles, look_base);
    return;
  }
  std::vector<int32_t> texture_id(b.textures.size());
  for (size_t t = 0; t < b.textures.size(); ++t) {
    const SoupTexture& bt = b.textures[t];
    const auto same = std::find_if(a.textures.begin(), a.textures.end(), [&](const SoupTexture& at) {
      return !bt.source.empty() && at.source == bt.source && at.width == bt.width && at.height == bt.height;
    });
    texture_id[t] = int32_t(same - a.textures.begin());
    if (same == a.textures.end()) a.textures.push_back(bt);
  }
  for (SurfaceLook look : b.looks) {
    if (look.texture >= 0 && size_t(look.texture) < texture_id.size())
      look.texture = texture_id[look.texture];
    a.looks.push_back(look);
  }
  if (b.triangle_look.empty()) {
    a.triangle_look.resize(a_triangles + b_triangles, look_base);
  } else {
    a.triangle_look.reserve(a_triangles + b_triangles);
    for (uint32_t l : b.triangle_look) a.triangle_look.push_back(l + look_base);
  }
}

}  // namespace

void TriangleSoup::append(const TriangleSoup& other, const glm::mat4& transform, uint32_t material) {
  append_colors(colors, positions.size(), triangles.size(), other.colors, other.positions.size(),
                other.triangles.size());
  const uint32_t base = static_cast<uint32_t>(positions.size());
  positions.reserve(positions.size() + other.positions.size());
  if (transform == glm::mat4(1.0f) && other.anchor == anchor) {
    positions.insert(positions.end(), other.positions.begin(), other.positions.end());
  } else {
    const glm::dmat4 t(transform);
    for (const glm::vec4& p : other.positions) {
      const glm::dvec4 q = t * glm::dvec4(other.anchor + glm::dvec3(glm::vec3(p)), 1.0);
      positions.push_back(glm::vec4(glm::vec3(glm::dvec3(q) / q.w - anchor), 1.0f));
    }
  }
  triangles.reserve(triangles.size() + other.triangles.size());
  for (const glm::uvec4& t : other.triangles)
    triangles.push_back({t.x + base, t.y + base, t.z + base, material == kKeepMaterial ? t.w : material});
}

namespace {

// The first triangle at fault, as validate_soup reports it.
[[noreturn]] void fail_soup(const TriangleSoup& soup, const std::string& source) {
  for (size_t i = 0; i < soup.triangles.size(); ++i) {
    const glm::uvec4& t = soup.triangles[i];
    for (int c = 0; c < 3; ++c) {
      if (t[c] >= soup.positions.size())
        fail("{}: triangle {} uses vertex {} but there are only {} vertices", source, i, t[c],
             soup.positions.size());
      const glm::vec3 v(soup.positions[t[c]]);
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        fail("{}: vertex {} of triangle {} is not finite ({}, {}, {})", source, t[c], i, v.x, v.y, v.z);
    }
  }
  throw InternalError("fail_soup: no triangle at fault");
}

}  // namespace

namespace {

// The colour arrays against the soup's (triangle_soup.h SoupColors).
void validate_colors(const TriangleSoup& soup, const std::string& source) {
  const SoupColors& c = soup.colors;
  const size_t v = soup.positions.size(), t = soup.triangles.size();
  if (!c.vertex_rgba.empty() && c.vertex_rgba.size() != v)
    fail("{}: {} vertex colours for {} vertices", source, c.vertex_rgba.size(), v);
  if (!c.vertex_uv.empty() && c.vertex_uv.size() != v)
    fail("{}: {} texture coordinates for {} vertices", source, c.vertex_uv.size(), v);
  for (size_t i = 0; i < c.vertex_uv.size(); ++i)
    if (!std::isfinite(c.vertex_uv[i].x) || !std::isfinite(c.vertex_uv[i].y))
      fail("{}: vertex {} has texture coordinates ({}, {}) that are not finite", source, i, c.vertex_uv[i].x,
           c.vertex_uv[i].y);
  if (!c.triangle_look.empty() && c.triangle_look.size() != t)
    fail("{}: {} triangle looks for {} triangles", source, c.triangle_look.size(), t);
  for (size_t i = 0; i < c.triangle_look.size(); ++i)
    if (c.triangle_look[i] >= c.looks.size())
      fail("{}: triangle {} uses look {} but there are {} looks", source, i, c.triangle_look[i],
           c.looks.size());
  for (size_t i = 0; i < c.looks.size(); ++i)
    if (c.looks[i].texture < -1 ||
        (c.looks[i].texture >= 0 && size_t(c.looks[i].texture) >= c.textures.size()))
      fail("{}: look {} uses texture {} but there are {} textures", source, i, c.looks[i].texture,
           c.textures.size());
  for (size_t i = 0; i < c.textures.size(); ++i) {
    const SoupTexture& tex = c.textures[i];
    if (tex.width == 0 || tex.height == 0 || uint64_t(tex.width) * tex.height != tex.texels.size())
      fail("{}: texture {} ({}) has {} texels for {}x{}", source, i, tex.source, tex.texels.size(), tex.width,
           tex.height);
  }
}

}  // namespace

size_t validate_soup(const TriangleSoup& soup, const std::string& source) {
  if (soup.triangles.empty()) fail("{}: the mesh has no triangles", source);
  if (!soup.colors.empty() || !soup.colors.vertex_uv.empty() || !soup.colors.triangle_look.empty())
    validate_colors(soup, source);
  const size_t n = soup.positions.size();
  const glm::vec4* pos = soup.positions.data();
  auto finite = [](const glm::vec4& p) {
    return std::isfinite(p.x) & std::isfinite(p.y) & std::isfinite(p.z);
  };
  bool all_finite = true;
  for (const glm::vec4& p : soup.positions) all_finite &= finite(p);
  if (!all_finite)  // allowed where no triangle uses the vertex
    for (const glm::uvec4& t : soup.triangles)
      for (int c = 0; c < 3; ++c)
        if (t[c] >= n || !finite(pos[t[c]])) fail_soup(soup, source);
  size_t degenerate = 0;
  for (size_t i = 0; i < soup.triangles.size(); ++i) {
    prefetch_corners(soup, i + kPrefetchAhead);
    const glm::uvec4& t = soup.triangles[i];
    if (t.x >= n || t.y >= n || t.z >= n) fail_soup(soup, source);
    const Float4 a = load(pos[t.x]), e1 = load(pos[t.y]) - a, e2 = load(pos[t.z]) - a;
    degenerate +=
        glm::cross(glm::vec3(e1[0], e1[1], e1[2]), glm::vec3(e2[0], e2[1], e2[2])) == glm::vec3(0.0f);
  }
  return degenerate;
}

}  // namespace voxr
