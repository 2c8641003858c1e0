#include "core/triangle_soup.h"

#include <cmath>

#include "core/error.h"

namespace voxr {

Bounds TriangleSoup::bounds() const {
  Bounds b;
  for (const glm::uvec4& t : triangles)
    for (int c = 0; c < 3; ++c) b.extend(glm::vec3(positions[t[c]]));
  return b;
}

void TriangleSoup::append(const TriangleSoup& other, const glm::mat4& transform, uint32_t material) {
  const uint32_t base = static_cast<uint32_t>(positions.size());
  positions.reserve(positions.size() + other.positions.size());
  for (const glm::vec4& p : other.positions) {
    glm::vec4 q = transform * glm::vec4(glm::vec3(p), 1.0f);
    positions.push_back(glm::vec4(glm::vec3(q) / q.w, 1.0f));
  }
  triangles.reserve(triangles.size() + other.triangles.size());
  for (const glm::uvec4& t : other.triangles)
    triangles.push_back({t.x + base, t.y + base, t.z + base, material == kKeepMaterial ? t.w : material});
}

size_t validate_soup(const TriangleSoup& soup, const std::string& source) {
  if (soup.triangles.empty()) fail("{}: the mesh has no triangles", source);
  size_t degenerate = 0;
  for (size_t i = 0; i < soup.triangles.size(); ++i) {
    const glm::uvec4& t = soup.triangles[i];
    glm::vec3 v[3];
    for (int c = 0; c < 3; ++c) {
      if (t[c] >= soup.positions.size())
        fail("{}: triangle {} uses vertex {} but there are only {} vertices", source, i, t[c],
             soup.positions.size());
      v[c] = glm::vec3(soup.positions[t[c]]);
      if (!std::isfinite(v[c].x) || !std::isfinite(v[c].y) || !std::isfinite(v[c].z))
        fail("{}: vertex {} of triangle {} is not finite ({}, {}, {})", source, t[c], i, v[c].x, v[c].y,
             v[c].z);
    }
    if (glm::cross(v[1] - v[0], v[2] - v[0]) == glm::vec3(0.0f)) ++degenerate;
  }
  return degenerate;
}

}  // namespace voxr
