#include "core/subdivide.h"

#include <unordered_map>

#include "util/error.h"

namespace voxr {

namespace {

constexpr uint64_t kMaxElements = uint64_t(1) << 31;

TriangleSoup subdivide_once(const TriangleSoup& in) {
  TriangleSoup out;
  out.anchor = in.anchor;
  // A closed mesh has 3T/2 edges; an open one at most 3T.
  const size_t edge_guess = in.triangles.size() * 3 / 2 + 16;
  out.positions.reserve(in.positions.size() + edge_guess);
  out.positions.assign(in.positions.begin(), in.positions.end());
  out.triangles.reserve(in.triangles.size() * 4);
  // Colours: midpoints get the mean colour (per channel, rounded half up) and UV of their edge's ends, the
  // four triangles their parent's look.
  const SoupColors& cin = in.colors;
  SoupColors& cout = out.colors;
  cout.vertex_rgba = cin.vertex_rgba;
  cout.vertex_uv = cin.vertex_uv;
  cout.looks = cin.looks;
  cout.textures = cin.textures;
  std::unordered_map<uint64_t, uint32_t> midpoints;
  midpoints.reserve(edge_guess);
  auto midpoint = [&](uint32_t a, uint32_t b) {
    const uint64_t key = a < b ? (uint64_t(a) << 32 | b) : (uint64_t(b) << 32 | a);
    const auto [it, inserted] = midpoints.try_emplace(key, uint32_t(out.positions.size()));
    if (inserted) {
      out.positions.push_back(
          glm::vec4(0.5f * (glm::vec3(in.positions[a]) + glm::vec3(in.positions[b])), 1.0f));
      if (!cin.vertex_rgba.empty()) {
        const uint32_t x = cin.vertex_rgba[a], y = cin.vertex_rgba[b];
        uint32_t m = 0;
        for (int s = 0; s < 32; s += 8) m |= ((((x >> s) & 255u) + ((y >> s) & 255u) + 1u) >> 1) << s;
        cout.vertex_rgba.push_back(m);
      }
      if (!cin.vertex_uv.empty()) cout.vertex_uv.push_back(0.5f * (cin.vertex_uv[a] + cin.vertex_uv[b]));
    }
    return it->second;
  };
  for (size_t i = 0; i < in.triangles.size(); ++i) {
    const glm::uvec4& t = in.triangles[i];
    const uint32_t ab = midpoint(t.x, t.y), bc = midpoint(t.y, t.z), ca = midpoint(t.z, t.x);
    out.triangles.push_back({t.x, ab, ca, t.w});
    out.triangles.push_back({ab, t.y, bc, t.w});
    out.triangles.push_back({ca, bc, t.z, t.w});
    out.triangles.push_back({ab, bc, ca, t.w});
    if (!cin.triangle_look.empty())
      cout.triangle_look.insert(cout.triangle_look.end(), 4, cin.triangle_look[i]);
  }
  return out;
}

}  // namespace

TriangleSoup subdivide_midpoint(const TriangleSoup& soup, int levels) {
  if (levels < 0) fail("subdivision levels must be >= 0, not {}", levels);
  if (levels == 0) return soup;
  uint64_t triangles = soup.triangles.size(), vertices = soup.positions.size();
  for (int l = 0; l < levels; ++l) {
    vertices += 3 * triangles;  // bound: every edge distinct
    triangles *= 4;
    if (triangles > kMaxElements || vertices > kMaxElements)
      fail("subdividing {} triangles {} times gives more than 2^31 triangles or vertices",
           soup.triangles.size(), levels);
  }
  TriangleSoup out = subdivide_once(soup);
  for (int l = 1; l < levels; ++l) out = subdivide_once(out);
  return out;
}

}  // namespace voxr
