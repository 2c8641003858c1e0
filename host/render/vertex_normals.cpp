#include "render/vertex_normals.h"

#include <algorithm>
#include <cmath>

namespace voxr {

std::vector<glm::vec3> vertex_normals(const TriangleSoup& soup) {
  std::vector<glm::dvec3> sum(soup.positions.size(), glm::dvec3(0.0));
  for (const glm::uvec4& t : soup.triangles) {
    const glm::dvec3 p[3] = {glm::dvec3(glm::vec3(soup.positions[t.x])),
                             glm::dvec3(glm::vec3(soup.positions[t.y])),
                             glm::dvec3(glm::vec3(soup.positions[t.z]))};
    const glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
    const double length = glm::length(n);
    if (!(length > 0.0)) continue;
    const glm::dvec3 unit = n / length;
    for (int c = 0; c < 3; ++c) {
      const glm::dvec3 a = p[(c + 1) % 3] - p[c], b = p[(c + 2) % 3] - p[c];
      const double la = glm::length(a), lb = glm::length(b);
      if (!(la > 0.0 && lb > 0.0)) continue;
      const double angle = std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.0, 1.0));
      sum[t[c]] += unit * angle;
    }
  }
  std::vector<glm::vec3> normals(sum.size(), glm::vec3(0.0f, 0.0f, 1.0f));
  for (size_t v = 0; v < sum.size(); ++v) {
    const double length = glm::length(sum[v]);
    if (length > 0.0) normals[v] = glm::vec3(sum[v] / length);
  }
  return normals;
}

}  // namespace voxr
