#include "core/mesh_topology.h"

#include <algorithm>
#include <unordered_map>

namespace voxr {

MeshTopology mesh_topology(const TriangleSoup& soup, uint32_t material) {
  auto key = [](uint32_t a, uint32_t b) { return (uint64_t(a) << 32) | b; };
  std::unordered_map<uint64_t, int> undirected, directed;
  undirected.reserve(soup.triangles.size() * 2);
  directed.reserve(soup.triangles.size() * 4);
  for (const glm::uvec4& t : soup.triangles) {
    if (material != TriangleSoup::kKeepMaterial && t.w != material) continue;
    for (int c = 0; c < 3; ++c) {
      const uint32_t a = t[c], b = t[(c + 1) % 3];
      ++undirected[key(std::min(a, b), std::max(a, b))];
      ++directed[key(a, b)];
    }
  }
  MeshTopology topology;
  for (const auto& [edge, n] : undirected) {
    topology.boundary += n == 1;
    topology.nonmanifold += n > 2;
  }
  for (const auto& [edge, n] : directed) topology.misoriented += n > 1;
  return topology;
}

double signed_volume(const TriangleSoup& soup) {
  double v = 0.0;
  for (const glm::uvec4& t : soup.triangles) {
    const glm::dvec3 a(soup.positions[t.x]), b(soup.positions[t.y]), c(soup.positions[t.z]);
    v += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  return v;
}

}  // namespace voxr
