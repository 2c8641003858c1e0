#include "core/mesh_topology.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <memory>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

namespace voxr {

namespace {

// Edge counts with the vertex pairs of the first boundary and non-manifold edge.
struct EdgeCounts : MeshTopology {
  std::pair<uint32_t, uint32_t> first_boundary{0, 0}, first_nonmanifold{0, 0};
};

// An edge's use by one triangle, filed under the edge's lower vertex: (higher vertex << 1) | 1 when the
// triangle runs from the lower vertex to the higher one. Equal values are uses of the same directed edge.
template <typename Use>
Use edge_use(uint32_t from, uint32_t to) {
  return (Use(std::max(from, to)) << 1) | Use(from < to);
}

// Counts the edges of one lower vertex from its uses, sorted so that uses of an edge are adjacent. An edge
// from a vertex to itself only has backward uses, so its directed count is its count, as it should be.
template <typename Use>
void count_edges(EdgeCounts& topology, uint32_t lower, Use* begin, Use* end) {
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
    if (n == 1 && topology.boundary++ == 0) topology.first_boundary = {lower, uint32_t(*begin >> 1)};
    if (n > 2 && topology.nonmanifold++ == 0) topology.first_nonmanifold = {lower, uint32_t(*begin >> 1)};
    topology.misoriented += (forward > 1) + (n - forward > 1);
    begin = run;
  }
}

// A counting sort of the edge uses by lower vertex (a handful each), then a small sort per vertex: far faster
// than hashing millions of edges. Needs vertex indices below 2^31 and fewer than 2^32 uses.
template <typename Counted>
EdgeCounts count_by_vertex(const TriangleSoup& soup, Counted counted, size_t vertices, size_t uses) {
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
  EdgeCounts topology;
  for (size_t v = 0; v < vertices; ++v)
    count_edges(topology, uint32_t(v), edges.get() + (v == 0 ? 0 : next[v - 1]), edges.get() + next[v]);
  return topology;
}

// The general case, for indices far beyond the number of uses (a soup not validated yet) or of 2^31 and more:
// one sort of (lower vertex, use) pairs.
template <typename Counted>
EdgeCounts count_by_sort(const TriangleSoup& soup, Counted counted, size_t uses) {
  std::vector<std::pair<uint32_t, uint64_t>> keys;
  keys.reserve(uses);
  for (const glm::uvec4& t : soup.triangles)
    if (counted(t))
      for (int c = 0; c < 3; ++c) {
        const uint32_t a = t[c], b = t[(c + 1) % 3];
        keys.emplace_back(std::min(a, b), edge_use<uint64_t>(a, b));
      }
  std::sort(keys.begin(), keys.end());
  EdgeCounts topology;
  std::vector<uint64_t> group;
  for (size_t i = 0, j = 0; i < keys.size(); i = j) {
    group.clear();
    for (j = i; j < keys.size() && keys[j].first == keys[i].first; ++j) group.push_back(keys[j].second);
    count_edges(topology, keys[i].first, group.data(), group.data() + group.size());
  }
  return topology;
}

// Edge counts by vertex index.
EdgeCounts count_indexed(const TriangleSoup& soup, uint32_t material) {
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

struct PositionHash {
  size_t operator()(const glm::vec3& p) const {
    uint32_t bits[3];
    for (int c = 0; c < 3; ++c) {
      const float v = p[c] == 0.0f ? 0.0f : p[c];  // -0 and +0 are one position
      std::memcpy(&bits[c], &v, 4);
    }
    uint64_t h = bits[0] * 0x9e3779b97f4a7c15ull;
    h = (h ^ bits[1]) * 0xff51afd7ed558ccdull;
    h = (h ^ bits[2]) * 0xc4ceb9fe1a85ec53ull;
    return size_t(h ^ (h >> 32));
  }
};

// For each vertex the first vertex at the same position.
std::vector<uint32_t> weld(const TriangleSoup& soup) {
  std::vector<uint32_t> id(soup.positions.size());
  std::unordered_map<glm::vec3, uint32_t, PositionHash> first;
  first.reserve(soup.positions.size());
  for (size_t i = 0; i < soup.positions.size(); ++i)
    id[i] = first.try_emplace(glm::vec3(soup.positions[i]), uint32_t(i)).first->second;
  return id;
}

// A triangle's welded corners as their smallest rotation (orientation kept): equal keys are the same
// triangle in the same orientation.
struct TriangleKey {
  uint32_t a, b, c;
  bool operator==(const TriangleKey&) const = default;
};
struct TriangleKeyHash {
  size_t operator()(const TriangleKey& k) const {
    uint64_t h = (uint64_t(k.a) * 0x9e3779b97f4a7c15ull) ^ (uint64_t(k.b) * 0xc2b2ae3d27d4eb4full);
    return size_t((h ^ (uint64_t(k.c) * 0x165667b19e3779f9ull)) ^ (h >> 29));
  }
};
TriangleKey key_of(uint32_t x, uint32_t y, uint32_t z) {
  auto less = [](const TriangleKey& a, const TriangleKey& b) {
    return std::tie(a.a, a.b, a.c) < std::tie(b.a, b.b, b.c);
  };
  return std::min({TriangleKey{x, y, z}, TriangleKey{y, z, x}, TriangleKey{z, x, y}}, less);
}
}  // namespace

std::string MeshTopology::describe(const glm::dvec3& anchor) const {
  std::string s;
  auto add = [&](const std::string& part) { s += (s.empty() ? "" : ", ") + part; };
  auto at = [&](const glm::vec3& p) {
    const glm::dvec3 w = anchor + glm::dvec3(p);
    return fmt::format("(first at {:.9g}, {:.9g}, {:.9g})", w.x, w.y, w.z);
  };
  if (boundary) add(fmt::format("{} boundary edges {}", boundary, at(boundary_at)));
  if (nonmanifold) add(fmt::format("{} non-manifold edges {}", nonmanifold, at(nonmanifold_at)));
  if (duplicates)
    add(fmt::format("{} triangles listed twice (first: triangle {})", duplicates, first_duplicate));
  if (opposite_pairs) add(fmt::format("{} pairs of opposite triangles on the same corners", opposite_pairs));
  return s.empty() ? "closed" : s;
}

MeshTopology mesh_topology(const TriangleSoup& soup, uint32_t material) {
  EdgeCounts indexed = count_indexed(soup, material);
  auto midpoint = [&](std::pair<uint32_t, uint32_t> e) {
    const size_t n = soup.positions.size();
    if (e.first >= n || e.second >= n) return glm::vec3(0.0f);
    return 0.5f * (glm::vec3(soup.positions[e.first]) + glm::vec3(soup.positions[e.second]));
  };
  if (indexed.closed()) return indexed;  // the common case: no welding needed
  // Weld by position, then set duplicates and cancelling pairs aside before counting edges again.
  const std::vector<uint32_t> id = weld(soup);
  TriangleSoup welded;
  welded.triangles.reserve(soup.triangles.size());
  std::unordered_map<TriangleKey, size_t, TriangleKeyHash> seen;  // key -> index in welded.triangles
  seen.reserve(soup.triangles.size());
  std::vector<bool> removed;
  MeshTopology result;
  for (size_t i = 0; i < soup.triangles.size(); ++i) {
    const glm::uvec4& t = soup.triangles[i];
    if (material != TriangleSoup::kKeepMaterial && t.w != material) continue;
    auto welded_id = [&](uint32_t v) { return v < id.size() ? id[v] : v; };  // unvalidated soups too
    const uint32_t x = welded_id(t.x), y = welded_id(t.y), z = welded_id(t.z);
    const TriangleKey key = key_of(x, y, z);
    if (seen.count(key)) {
      if (result.duplicates++ == 0) result.first_duplicate = i;
      continue;
    }
    const auto reverse = seen.find(key_of(x, z, y));
    if (reverse != seen.end() && !removed[reverse->second]) {
      removed[reverse->second] = true;
      ++result.opposite_pairs;
      continue;
    }
    seen.emplace(key, welded.triangles.size());
    welded.triangles.push_back(glm::uvec4(x, y, z, 0u));
    removed.push_back(false);
  }
  size_t kept = 0;
  for (size_t i = 0; i < welded.triangles.size(); ++i)
    if (!removed[i]) welded.triangles[kept++] = welded.triangles[i];
  welded.triangles.resize(kept);
  const EdgeCounts counts = count_indexed(welded, TriangleSoup::kKeepMaterial);
  result.boundary = counts.boundary;
  result.nonmanifold = counts.nonmanifold;
  result.misoriented = counts.misoriented;
  result.boundary_at = midpoint(counts.first_boundary);
  result.nonmanifold_at = midpoint(counts.first_nonmanifold);
  return result;
}

size_t drop_duplicate_triangles(TriangleSoup& soup) {
  const std::vector<uint32_t> id = weld(soup);
  std::unordered_set<TriangleKey, TriangleKeyHash> seen;
  seen.reserve(soup.triangles.size());
  size_t kept = 0;
  HostArray<uint32_t>& looks = soup.colors.triangle_look;  // kept parallel to the triangles
  for (size_t i = 0; i < soup.triangles.size(); ++i) {
    const glm::uvec4 t = soup.triangles[i];
    if (!seen.insert(key_of(id[t.x], id[t.y], id[t.z])).second) continue;
    if (!looks.empty()) looks[kept] = looks[i];
    soup.triangles[kept++] = t;
  }
  const size_t removed = soup.triangles.size() - kept;
  soup.triangles.resize(kept);
  if (!looks.empty()) looks.resize(kept);
  return removed;
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
