// mesh_topology against the plain definition (edge use counts kept in maps) on soups that hit every case:
// shared and repeated vertices, closed, open and non-manifold meshes, material filters, sparse indices.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/generators.h"
#include "core/mesh_topology.h"

namespace voxr {
namespace {

// Edge use counts over `triangles`.
MeshTopology count_edges(const std::vector<glm::uvec4>& triangles) {
  std::map<std::pair<uint32_t, uint32_t>, int> undirected, directed;
  for (const glm::uvec4& t : triangles) {
    for (int c = 0; c < 3; ++c) {
      const uint32_t a = t[c], b = t[(c + 1) % 3];
      ++undirected[{std::min(a, b), std::max(a, b)}];
      ++directed[{a, b}];
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

// The definition: edges by vertex index; when they are not closed, again over welded positions with
// same-orientation copies and opposite-orientation pairs set aside (a triangle is the same as another when
// its welded corners are a rotation of the other's; the reverse when a rotation of the other's reversed).
MeshTopology reference_topology(const TriangleSoup& soup, uint32_t material) {
  std::vector<glm::uvec4> triangles;
  for (const glm::uvec4& t : soup.triangles)
    if (material == TriangleSoup::kKeepMaterial || t.w == material) triangles.push_back(t);
  const MeshTopology indexed = count_edges(triangles);
  if (indexed.closed()) return indexed;
  std::map<std::tuple<float, float, float>, uint32_t> first;
  auto weld = [&](uint32_t v) {
    if (v >= soup.positions.size()) return v;
    const glm::vec4 p = soup.positions[v] + glm::vec4(0.0f);  // -0 -> +0
    return first.try_emplace({p.x, p.y, p.z}, v).first->second;
  };
  auto rotations = [](uint32_t a, uint32_t b, uint32_t c) {
    return std::vector<std::array<uint32_t, 3>>{{a, b, c}, {b, c, a}, {c, a, b}};
  };
  std::vector<glm::uvec4> kept;
  std::vector<bool> cancelled;
  MeshTopology result;
  for (const glm::uvec4& t : triangles) {
    const uint32_t a = weld(t.x), b = weld(t.y), c = weld(t.z);
    bool copy = false, pair = false;
    for (size_t i = 0; i < kept.size(); ++i)
      for (const auto& r : rotations(kept[i].x, kept[i].y, kept[i].z))
        copy |= r == std::array<uint32_t, 3>{a, b, c};
    for (size_t i = 0; i < kept.size() && !copy && !pair; ++i)
      for (const auto& r : rotations(kept[i].x, kept[i].y, kept[i].z))
        if (!cancelled[i] && r == std::array<uint32_t, 3>{a, c, b}) cancelled[i] = pair = true;
    result.duplicates += copy;
    result.opposite_pairs += pair;
    if (!copy && !pair) {
      kept.push_back({a, b, c, 0});
      cancelled.push_back(false);
    }
  }
  std::vector<glm::uvec4> remaining;
  for (size_t i = 0; i < kept.size(); ++i)
    if (!cancelled[i]) remaining.push_back(kept[i]);
  const MeshTopology welded = count_edges(remaining);
  result.boundary = welded.boundary;
  result.nonmanifold = welded.nonmanifold;
  result.misoriented = welded.misoriented;
  return result;
}

std::string str(const MeshTopology& t) {
  return "boundary " + std::to_string(t.boundary) + ", nonmanifold " + std::to_string(t.nonmanifold) +
         ", misoriented " + std::to_string(t.misoriented) + ", duplicates " + std::to_string(t.duplicates) +
         ", opposite pairs " + std::to_string(t.opposite_pairs);
}

// Equal to the definition for all triangles and for each material in use.
void expect_as_defined(const TriangleSoup& soup, const std::string& what) {
  for (uint32_t material : {TriangleSoup::kKeepMaterial, 0u, 1u, 2u}) {
    SCOPED_TRACE(what + ", material " + std::to_string(material));
    EXPECT_EQ(str(mesh_topology(soup, material)), str(reference_topology(soup, material)));
  }
}

// Triangles over a few shared vertices: repeated edges in both directions, edges from a vertex to itself.
TriangleSoup random_shared(uint32_t seed, uint32_t vertices, size_t triangles, uint32_t offset = 0) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<uint32_t> vertex(offset, offset + vertices - 1), material(0, 2);
  TriangleSoup soup;
  for (uint32_t v = 0; v < offset + vertices; ++v)  // a few positions repeat: welding joins those vertices
    soup.positions.push_back(glm::vec4(float(v % (vertices - 1)), float(v % 3), 0.0f, 1.0f));
  for (size_t i = 0; i < triangles; ++i)
    soup.triangles.push_back({vertex(rng), vertex(rng), vertex(rng), material(rng)});
  return soup;
}

// An n x n grid of quads, two triangles each, consistently wound.
TriangleSoup sheet(uint32_t n, uint32_t material = 0) {
  TriangleSoup soup;
  for (uint32_t j = 0; j <= n; ++j)
    for (uint32_t i = 0; i <= n; ++i) soup.positions.push_back(glm::vec4(float(i), float(j), 0.0f, 1.0f));
  auto v = [n](uint32_t i, uint32_t j) { return j * (n + 1) + i; };
  for (uint32_t j = 0; j < n; ++j)
    for (uint32_t i = 0; i < n; ++i) {
      soup.triangles.push_back({v(i, j), v(i + 1, j), v(i + 1, j + 1), material});
      soup.triangles.push_back({v(i, j), v(i + 1, j + 1), v(i, j + 1), material});
    }
  return soup;
}

TEST(MeshTopology, RandomSoupsCountAsDefined) {
  for (uint32_t seed = 1; seed <= 200; ++seed) {
    const uint32_t vertices = 3 + seed % 25;
    expect_as_defined(random_shared(seed, vertices, 1 + seed % 120), "seed " + std::to_string(seed));
  }
  // Many uses per vertex (the per-vertex sort's large case) and dense reuse.
  expect_as_defined(random_shared(1001, 6, 500), "6 vertices, 500 triangles");
  expect_as_defined(random_shared(1002, 40, 3000), "40 vertices, 3000 triangles");
}

TEST(MeshTopology, SparseAndHugeIndicesCountAsDefined) {
  // Indices far beyond the number of edges, up to the largest uint32: the sort-based count.
  TriangleSoup soup = random_shared(7, 30, 200);
  for (glm::uvec4& t : soup.triangles)
    for (int c = 0; c < 3; ++c) t[c] = t[c] % 2 ? 4000000000u + t[c] : (1u << 31) + t[c];
  expect_as_defined(soup, "indices near 2^31 and 4e9");
  soup.triangles.push_back({0xffffffffu, 0xfffffffeu, 0, 1});
  expect_as_defined(soup, "index 2^32 - 1");
  expect_as_defined(random_shared(8, 20, 100, 100000), "indices from 100000");
  expect_as_defined(random_shared(9, 20, 100, 2000), "indices from 2000 (many vertices without edges)");
}

TEST(MeshTopology, ClosedOpenAndNonManifoldMeshes) {
  const TriangleSoup box = make_box();
  EXPECT_EQ(str(mesh_topology(box)), str(MeshTopology{}));
  expect_as_defined(box, "box");

  TriangleSoup flipped = box;
  std::swap(flipped.triangles[3].y, flipped.triangles[3].z);
  EXPECT_EQ(str(mesh_topology(flipped)), str(MeshTopology{0, 0, 3}));
  expect_as_defined(flipped, "box with a flipped triangle");

  const TriangleSoup open = sheet(5);
  EXPECT_EQ(str(mesh_topology(open)), str(MeshTopology{20, 0, 0}));
  expect_as_defined(open, "sheet");

  // Three triangles on edge 0-1 (two of them the same way round), then a fan of 30 around vertex 0.
  TriangleSoup fan;
  for (uint32_t k = 0; k < 40; ++k)
    fan.positions.push_back(glm::vec4(float(k), float(k * k % 5), 0.0f, 1.0f));
  fan.triangles = {{0, 1, 2, 0}, {1, 0, 3, 0}, {0, 1, 4, 0}};
  EXPECT_EQ(str(mesh_topology(fan)), str(MeshTopology{6, 1, 1}));
  for (uint32_t k = 5; k < 35; ++k) fan.triangles.push_back({0, k, k + 1, 1});
  expect_as_defined(fan, "non-manifold fan");

  // The material filter: a closed box and an open sheet in one soup.
  TriangleSoup both = sheet(3, 2);
  both.append(make_box(), glm::mat4(1.0f), 1);
  EXPECT_TRUE(mesh_topology(both, 1).closed_and_oriented());
  EXPECT_EQ(mesh_topology(both, 2).boundary, 12u);
  EXPECT_EQ(mesh_topology(both).boundary, 12u);
  EXPECT_EQ(str(mesh_topology(both, 7)), str(MeshTopology{}));
  expect_as_defined(both, "box and sheet");
  EXPECT_EQ(str(mesh_topology(TriangleSoup())), str(MeshTopology{}));
}

// Every triangle with its own three vertices, as STL and some exporters write them.
TriangleSoup unshared(const TriangleSoup& soup) {
  TriangleSoup out;
  for (const glm::uvec4& t : soup.triangles) {
    const uint32_t base = uint32_t(out.positions.size());
    for (int c = 0; c < 3; ++c) out.positions.push_back(soup.positions[t[c]]);
    out.triangles.push_back({base, base + 1, base + 2, t.w});
  }
  return out;
}

TEST(MeshTopology, ClosureIsJudgedOnPositions) {
  const TriangleSoup box = unshared(make_box());
  EXPECT_EQ(str(mesh_topology(box)), str(MeshTopology{}));
  expect_as_defined(box, "box without shared vertices");
  TriangleSoup open = box;
  open.triangles.pop_back();
  const MeshTopology t = mesh_topology(open);
  EXPECT_EQ(t.boundary, 3u);
  // The warning names what was found and where (an edge of the missing triangle, world coordinates).
  const std::string text = t.describe(glm::dvec3(3000.0, 0.0, 0.0));
  EXPECT_TRUE(text.find("3 boundary edges (first at 3000") != std::string::npos ||
              text.find("3 boundary edges (first at 2999.5") != std::string::npos)
      << text;
}

TEST(MeshTopology, DuplicatesAreSetAsideAsTheWindingNumberDoes) {
  // Case c20: a closed box with one triangle listed twice is closed, with one duplicate.
  TriangleSoup box = make_box();
  box.triangles.push_back(box.triangles[4]);
  EXPECT_EQ(str(mesh_topology(box)), str(MeshTopology{0, 0, 0, 1, 0}));
  EXPECT_EQ(mesh_topology(box).first_duplicate, box.triangles.size() - 1);
  EXPECT_NE(
      mesh_topology(box).describe(glm::dvec3(0.0)).find("1 triangles listed twice (first: triangle 12)"),
      std::string::npos);
  expect_as_defined(box, "box with a duplicate");
  // The same copy with rotated corners and its own vertices is the same triangle.
  TriangleSoup rotated = unshared(make_box());
  const glm::uvec4 t = rotated.triangles[4];
  rotated.triangles.push_back({t.y, t.z, t.x, t.w});
  EXPECT_EQ(str(mesh_topology(rotated)), str(MeshTopology{0, 0, 0, 1, 0}));
  // A triangle and its reverse added to an open sheet cancel.
  TriangleSoup sheet_pair = sheet(2);
  sheet_pair.positions.push_back(glm::vec4(0.0f, 0.0f, 5.0f, 1.0f));
  const uint32_t apex = uint32_t(sheet_pair.positions.size() - 1);
  sheet_pair.triangles.push_back({0, 1, apex, 0});
  sheet_pair.triangles.push_back({1, 0, apex, 0});
  EXPECT_EQ(str(mesh_topology(sheet_pair)), str(MeshTopology{8, 0, 0, 0, 1}));
  expect_as_defined(sheet_pair, "sheet with a cancelling pair");

  EXPECT_EQ(drop_duplicate_triangles(box), 1u);
  EXPECT_EQ(box.triangles.size(), make_box().triangles.size());
  EXPECT_TRUE(mesh_topology(box).closed_and_oriented());
  EXPECT_EQ(drop_duplicate_triangles(rotated), 1u);
}

}  // namespace
}  // namespace voxr
