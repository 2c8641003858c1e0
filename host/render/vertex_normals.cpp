#include "render/vertex_normals.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace voxr {

std::vector<glm::vec3> vertex_normals(const TriangleSoup& soup) {
  const size_t n = soup.positions.size();
  std::vector<glm::dvec3> sums(n, glm::dvec3(0.0));
  for (size_t i = 0; i < soup.triangles.size(); ++i) {
    const glm::uvec4& t = soup.triangles[i];
    if (t.x >= n || t.y >= n || t.z >= n)
      fail("vertex_normals: triangle {} names vertex {} of {}", i, std::max({t.x, t.y, t.z}), n);
    const glm::dvec3 p[3] = {glm::dvec3(soup.positions[t.x]), glm::dvec3(soup.positions[t.y]),
                             glm::dvec3(soup.positions[t.z])};
    const glm::dvec3 cross = glm::cross(p[1] - p[0], p[2] - p[0]);
    const double area2 = glm::length(cross);
    if (!(area2 > 0.0)) continue;  // zero area (or NaN): no direction to contribute
    const glm::dvec3 unit = cross / area2;
    for (int c = 0; c < 3; ++c) {
      const glm::dvec3 a = p[(c + 1) % 3] - p[c], b = p[(c + 2) % 3] - p[c];
      // The angle at corner c, accurate for slivers too (atan2 of |a x b| and a . b).
      const double angle = std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
      sums[t[c]] += angle * unit;
    }
  }
  std::vector<glm::vec3> normals(n);
  for (size_t v = 0; v < n; ++v) {
    const double len = glm::length(sums[v]);
    normals[v] = len > 0.0 ? glm::vec3(sums[v] / len) : glm::vec3(0.0f, 0.0f, 1.0f);
  }
  return normals;
}

}  // namespace voxr
