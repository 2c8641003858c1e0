#include "core/mesh_topology.h"

#include <algorithm>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

namespace voxr {

namespace {

// An edge's use by one triangle, filed under the edge's lower vertex: (higher vertex << 1) | 1 when the
// triangle runs from the lower vertex to the higher one. Equal values are uses of the same directed edge.
template <typename Use>
Use edge_use(uint32_t from, uint32_t to) {
  return (Use(std::max(from, to)) << 1) | Use(from < to);
}

// Counts the edges of one lower vertex from its uses, sorted so that uses of an edge are adjacent. An edge
// from a vertex to itself only has backward uses, so its directed count is its count, as it should be.
template <typename Use>
void count_edges(MeshTopology& topology, Use* begin, Use* end) {
  if (end - begin > 16) {
    std::sort(begin, end);
  } else {
    for (Use* i = begin + 1; i < end; ++i) {
      const Use use = *i;
      Use* j = i;
      for (; j > begin && j[-1] > use; --j) *j = j[-1];
      *j = use;
    }
  }
  while (begin != end) {
    Use* run = begin;
    size_t forward = 0;
    for (; run != end && (*run >> 1) == (*begin >> 1); ++run) forward += *run & 1;
    const size_t n = size_t(run - begin);
    topology.boundary += n == 1;
    topology.nonmanifold += n > 2;
    topology.misoriented += (forward > 1) + (n - forward > 1);
    begin = run;
  }
}

// A counting sort of the edge uses by lower vertex (a handful each), then a small sort per vertex: far faster
// than hashing millions of edges. Needs vertex indices below 2^31 and fewer than 2^32 uses.
template <typename Counted>
MeshTopology count_by_vertex(const TriangleSoup& soup, Counted counted, size_t vertices, size_t uses) {
  std::vector<uint32_t> next(vertices + 1, 0);
  for (const glm::uvec4& t : soup.triangles)
    if (counted(t))
      for (int c = 0; c < 3; ++c) ++next[std::min(t[c], t[(c + 1) % 3]) + 1];
  for (size_t v = 1; v <= vertices; ++v) next[v] += next[v - 1];
  const std::unique_ptr<uint32_t[]> edges =
      std::make_unique_for_overwrite<uint32_t[]>(uses);  // all written below
  for (const glm::uvec4& t : soup.triangles)
    if (counted(t))
      for (int c = 0; c < 3; ++c) {
        const uint32_t a = t[c], b = t[(c + 1) % 3];
        edges[next[std::min(a, b)]++] = edge_use<uint32_t>(a, b);
      }
  // next[v] has moved to the end of vertex v's uses, which is where vertex v + 1's begin.
  MeshTopology topology;
  for (size_t v = 0; v < vertices; ++v)
    count_edges(topology, edges.get() + (v == 0 ? 0 : next[v - 1]), edges.get() + next[v]);
  return topology;
}

// The general case, for indices far beyond the number of uses (a soup not validated yet) or of 2^31 and more:
// one sort of (lower vertex, use) pairs.
template <typename Counted>
MeshTopology count_by_sort(const TriangleSoup& soup, Counted counted, size_t uses) {
  std::vector<std::pair<uint32_t, uint64_t>> keys;
  keys.reserve(uses);
  for (const glm::uvec4& t : soup.triangles)
    if (counted(t))
      for (int c = 0; c < 3; ++c) {
        const uint32_t a = t[c], b = t[(c + 1) % 3];
        keys.emplace_back(std::min(a, b), edge_use<uint64_t>(a, b));
      }
  std::sort(keys.begin(), keys.end());
  MeshTopology topology;
  std::vector<uint64_t> group;
  for (size_t i = 0, j = 0; i < keys.size(); i = j) {
    group.clear();
    for (j = i; j < keys.size() && keys[j].first == keys[i].first; ++j) group.push_back(keys[j].second);
    count_edges(topology, group.data(), group.data() + group.size());
  }
  return topology;
}

}  // namespace

MeshTopology mesh_topology(const TriangleSoup& soup, uint32_t material) {
  auto counted = [material](const glm::uvec4& t) {
    return material == TriangleSoup::kKeepMaterial || t.w == material;
  };
  size_t uses = 0;
  uint32_t top = 0;
  for (const glm::uvec4& t : soup.triangles)
    if (counted(t)) {
      uses += 3;
      top = std::max({top, t.x, t.y, t.z});
    }
  if (uses == 0) return {};
  const size_t vertices = size_t(top) + 1;
  if (top >= (1u << 31) || uses > std::numeric_limits<uint32_t>::max() || vertices > 2 * uses + 4096)
    return count_by_sort(soup, counted, uses);
  return count_by_vertex(soup, counted, vertices, uses);
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
