// mesh_topology against the plain definition (edge use counts kept in maps) on soups that hit every case:
// shared and repeated vertices, closed, open and non-manifold meshes, material filters, sparse indices.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <string>
#include <utility>

#include "core/generators.h"
#include "core/mesh_topology.h"

namespace voxr {
namespace {

MeshTopology reference_topology(const TriangleSoup& soup, uint32_t material) {
  std::map<std::pair<uint32_t, uint32_t>, int> undirected, directed;
  for (const glm::uvec4& t : soup.triangles) {
    if (material != TriangleSoup::kKeepMaterial && t.w != material) continue;
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

std::string str(const MeshTopology& t) {
  return "boundary " + std::to_string(t.boundary) + ", nonmanifold " + std::to_string(t.nonmanifold) +
         ", misoriented " + std::to_string(t.misoriented);
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
  soup.positions.assign(offset + vertices, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));  // topology ignores them
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
  fan.positions.assign(40, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
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

}  // namespace
}  // namespace voxr
