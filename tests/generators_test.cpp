// Procedural meshes and midpoint subdivision: counts, closure, orientation, volume, determinism.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <map>
#include <numbers>
#include <tuple>
#include <utility>

#include "core/generators.h"
#include "core/mesh_topology.h"
#include "core/subdivide.h"
#include "util/error.h"

namespace voxr {
namespace {

constexpr double kPi = std::numbers::pi;

void expect_closed_and_outward(const TriangleSoup& soup, const char* what) {
  const MeshTopology e = mesh_topology(soup);
  EXPECT_EQ(e.boundary, 0u) << what;
  EXPECT_EQ(e.nonmanifold, 0u) << what;
  EXPECT_EQ(e.misoriented, 0u) << what;
  EXPECT_GT(signed_volume(soup), 0.0) << what;
  EXPECT_EQ(validate_soup(soup, what), 0u) << what << ": degenerate triangles";
}

bool same_soup(const TriangleSoup& a, const TriangleSoup& b) {
  return a.positions == b.positions && a.triangles == b.triangles;
}

// Area of the regular n-gon inscribed in the unit circle, over pi: the tessellation's volume factor.
double polygon_factor(int n) {
  return n * std::sin(2.0 * kPi / n) / (2.0 * kPi);
}

TEST(Generators, TorusHas800TrianglesClosedAndOutward) {
  const TriangleSoup torus = make_torus();
  EXPECT_EQ(torus.triangle_count(), 800u);
  EXPECT_EQ(torus.vertex_count(), 400u);
  expect_closed_and_outward(torus, "torus");
  const double exact = 2.0 * kPi * kPi * 1.0 * 0.4 * 0.4;
  const double v = signed_volume(torus);
  // Inscribed polygons lose about (2 pi / 20)^2 / 6 ~ 1.6% per direction.
  EXPECT_LT(v, exact);
  EXPECT_NEAR(v / exact, 1.0, 0.05);
  // Bounds: |x|, |z| <= R + r, |y| <= r.
  const Bounds b = torus.bounds();
  EXPECT_NEAR(b.hi.x, 1.4f, 1e-5f);
  EXPECT_NEAR(b.hi.y, 0.4f * std::sin(2.0f * float(kPi) * 5 / 20), 1e-5f);
}

TEST(Generators, TorusVolumeConvergesToAnalytic) {
  const double R = 2.0, r = 0.5;
  const double exact = 2.0 * kPi * kPi * R * r * r;
  const double v = signed_volume(make_torus(float(R), float(r), 120, 60));
  EXPECT_NEAR(v / exact, 1.0, 0.003);
  EXPECT_LT(v, exact);
}

TEST(Generators, GeneratorsAreDeterministic) {
  EXPECT_TRUE(same_soup(make_torus(), make_torus()));
  EXPECT_TRUE(same_soup(make_vase(), make_vase()));
  EXPECT_TRUE(same_soup(make_tree(1.0f, 42), make_tree(1.0f, 42)));
  EXPECT_FALSE(same_soup(make_tree(1.0f, 42), make_tree(1.0f, 43)));
}

TEST(Generators, SphereIsClosedWithSingleVertexPoles) {
  const int stacks = 16, slices = 32;
  const TriangleSoup sphere = make_uv_sphere(2.0f, stacks, slices);
  EXPECT_EQ(sphere.triangle_count(), size_t(2 * slices * (stacks - 1)));
  EXPECT_EQ(sphere.vertex_count(), size_t(slices * (stacks - 1) + 2));
  expect_closed_and_outward(sphere, "sphere");
  for (const glm::vec4& p : sphere.positions) EXPECT_NEAR(glm::length(glm::vec3(p)), 2.0f, 1e-5f);
  const double exact = 4.0 / 3.0 * kPi * 8.0;
  EXPECT_LT(signed_volume(sphere), exact);
  EXPECT_NEAR(signed_volume(sphere) / exact, 1.0, 0.03);
  // Smallest case: a double cone over a triangle.
  const TriangleSoup tiny = make_uv_sphere(1.0f, 2, 3);
  EXPECT_EQ(tiny.triangle_count(), 6u);
  expect_closed_and_outward(tiny, "tiny sphere");
}

TEST(Generators, BoxHasTwelveOutwardTriangles) {
  const glm::vec3 lo(-1.0f, 0.0f, 2.0f), hi(1.0f, 0.5f, 5.0f);
  const TriangleSoup box = make_box(lo, hi);
  EXPECT_EQ(box.triangle_count(), 12u);
  EXPECT_EQ(box.vertex_count(), 8u);
  expect_closed_and_outward(box, "box");
  EXPECT_NEAR(signed_volume(box), 2.0 * 0.5 * 3.0, 1e-5);
  const glm::vec3 center = 0.5f * (lo + hi);
  for (const glm::uvec4& t : box.triangles) {
    const glm::vec3 a(box.positions[t.x]), b(box.positions[t.y]), c(box.positions[t.z]);
    EXPECT_GT(glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0f - center), 0.0f);
  }
}

TEST(Generators, VaseIsClosedWithAWall) {
  const TriangleSoup vase = make_vase();
  expect_closed_and_outward(vase, "vase");
  const Bounds b = vase.bounds();
  EXPECT_FLOAT_EQ(b.lo.y, 0.0f);
  EXPECT_FLOAT_EQ(b.hi.y, 1.0f);

  // Straight profile: a cup. Between two rings the wall is a frustum of the inscribed polygon, so the
  // volume is exact: polygon area factor times (outer cylinder - inner cavity).
  VaseParams p;
  p.height = 2.0f;
  p.profile = {0.5f, 0.5f};
  p.thickness = 0.1f;
  p.segments = 24;
  p.rows = 3;
  const TriangleSoup cup = make_vase(p);
  expect_closed_and_outward(cup, "cup");
  const double R = 0.5, t = 0.1, H = 2.0;
  const double expected = polygon_factor(p.segments) * kPi * (R * R * H - (R - t) * (R - t) * (H - t));
  EXPECT_NEAR(signed_volume(cup) / expected, 1.0, 1e-5);
  // Outer surface, rim, inner surface, floor: rings = 2 * (rows + 1), all joined, two poles.
  EXPECT_EQ(cup.vertex_count(), size_t(2 * (p.rows + 1) * p.segments + 2));
}

TEST(Generators, VaseFilledWithALiquidSharesItsInnerFaces) {
  VaseParams p;
  p.height = 2.0f;
  p.profile = {0.5f, 0.5f};
  p.thickness = 0.1f;
  p.segments = 24;
  p.rows = 4;
  p.fill = 0.5f;
  const TriangleSoup glass = make_vase(p);
  p.fill = 0.0f;
  const TriangleSoup empty = make_vase(p);
  // The vase itself is unchanged; the liquid is material 1, closed and outward.
  ASSERT_GT(glass.triangle_count(), empty.triangle_count());
  for (size_t i = 0; i < empty.triangle_count(); ++i) EXPECT_EQ(glass.triangles[i], empty.triangles[i]);
  for (size_t i = 0; i < empty.vertex_count(); ++i) EXPECT_EQ(glass.positions[i], empty.positions[i]);
  TriangleSoup liquid;
  for (size_t i = empty.triangle_count(); i < glass.triangle_count(); ++i) {
    EXPECT_EQ(glass.triangles[i].w, 1u);
    liquid.triangles.push_back(glass.triangles[i]);
  }
  liquid.positions = glass.positions;
  expect_closed_and_outward(liquid, "liquid");
  // Fill 0.5 of rows 4: the inner surface up to row 2, y = 0.1 + 1.9 * 2 / 4. A cylinder of the inscribed
  // polygon: exact volume.
  const double r = 0.4, level = 0.1 + 1.9 * 0.5;
  EXPECT_NEAR(signed_volume(liquid) / (polygon_factor(p.segments) * kPi * r * r * (level - 0.1)), 1.0, 1e-5);
  // Every liquid vertex but its top centre is a vertex of the vase, bit for bit: the faces coincide.
  std::map<std::tuple<float, float, float>, int> vase_vertices;
  for (const glm::vec4& v : empty.positions) vase_vertices[{v.x, v.y, v.z}] = 1;
  size_t own = 0;
  for (size_t i = empty.vertex_count(); i < glass.vertex_count(); ++i) {
    const glm::vec4 v = glass.positions[i];
    if (!vase_vertices.count({v.x, v.y, v.z})) {
      ++own;
      EXPECT_FLOAT_EQ(v.x, 0.0f);
      EXPECT_NEAR(v.y, level, 1e-6);
    }
  }
  EXPECT_EQ(own, 1u);
}

TEST(Generators, TreeHasClosedTrunkAndSheetLeaves) {
  const TriangleSoup tree = make_tree(1.0f, 3);
  size_t leaf_triangles = 0;
  for (const glm::uvec4& t : tree.triangles) {
    ASSERT_TRUE(t.w == kTreeTrunkMaterial || t.w == kTreeLeafMaterial);
    leaf_triangles += t.w == kTreeLeafMaterial;
  }
  EXPECT_EQ(leaf_triangles, 2u * 300u);
  const MeshTopology trunk = mesh_topology(tree, kTreeTrunkMaterial);
  EXPECT_TRUE(trunk.closed());
  EXPECT_EQ(trunk.misoriented, 0u);
  // Leaves: open quads, each with 4 boundary edges and one shared diagonal.
  const MeshTopology leaves = mesh_topology(tree, kTreeLeafMaterial);
  EXPECT_EQ(leaves.boundary, 4u * 300u);
  EXPECT_EQ(leaves.misoriented, 0u);
  // Leaves sit in the crown, above the trunk's base.
  for (const glm::uvec4& t : tree.triangles) {
    if (t.w == kTreeLeafMaterial) {
      EXPECT_GT(tree.positions[t.x].y, 0.7f);
    }
  }
  // Density scales the leaf count; zero leaves just the trunk.
  const TriangleSoup bare = make_tree(0.0f, 3);
  EXPECT_EQ(tree.triangle_count() - bare.triangle_count(), 600u);
  EXPECT_EQ(make_tree(2.0f, 3).triangle_count() - bare.triangle_count(), 1200u);
}

TEST(Generators, FoliageFillsTheBoxWithSheetLeaves) {
  FoliageParams p;
  p.size = glm::vec3(2.0f, 1.0f, 1.5f);
  p.leaves = 500;
  p.leaf_size = 0.1f;
  p.seed = 5;
  const TriangleSoup block = make_foliage(p);
  EXPECT_EQ(block.triangle_count(), 2u * 500u);
  EXPECT_EQ(block.vertex_count(), 4u * 500u);
  for (const glm::uvec4& t : block.triangles) ASSERT_EQ(t.w, kFoliageLeafMaterial);
  // Open quads, each with 4 boundary edges and one shared diagonal, consistently wound.
  const MeshTopology e = mesh_topology(block);
  EXPECT_EQ(e.boundary, 4u * 500u);
  EXPECT_EQ(e.nonmanifold, 0u);
  EXPECT_EQ(e.misoriented, 0u);
  EXPECT_EQ(validate_soup(block, "foliage"), 0u);
  // Every vertex inside the box; the leaves spread over most of it.
  const glm::vec3 half = 0.5f * p.size;
  for (const glm::vec4& v : block.positions)
    ASSERT_TRUE(glm::all(glm::lessThanEqual(glm::abs(glm::vec3(v)), half + 1e-6f)))
        << v.x << " " << v.y << " " << v.z;
  const Bounds b = block.bounds();
  for (int a = 0; a < 3; ++a) {
    EXPECT_LT(b.lo[a], -0.9f * half[a]) << "axis " << a;
    EXPECT_GT(b.hi[a], 0.9f * half[a]) << "axis " << a;
  }
  // Leaf k is vertices 4k..4k+3: a rectangle of length in [0.75, 1.25) leaf sizes, half as wide.
  for (size_t k = 0; k < p.leaves; ++k) {
    const glm::vec3 v0(block.positions[4 * k]), v1(block.positions[4 * k + 1]),
        v2(block.positions[4 * k + 2]);
    const float length = glm::length(v1 - v0), width = glm::length(v2 - v1);
    ASSERT_GE(length, 0.75f * p.leaf_size - 1e-6f);
    ASSERT_LT(length, 1.25f * p.leaf_size + 1e-6f);
    ASSERT_NEAR(width, 0.5f * length, 1e-5f);
    ASSERT_NEAR(glm::dot(v1 - v0, v2 - v1), 0.0f, 1e-6f);
  }
  // Same parameters, same block; another seed, another block; no leaves, no triangles.
  EXPECT_TRUE(same_soup(make_foliage(p), block));
  p.seed = 6;
  EXPECT_FALSE(same_soup(make_foliage(p), block));
  p.leaves = 0;
  EXPECT_EQ(make_foliage(p).triangle_count(), 0u);
}

TEST(Generators, PlaneFacesUp) {
  const int n = 4;
  const TriangleSoup plane = make_plane(glm::vec2(4.0f, 2.0f), n);
  EXPECT_EQ(plane.triangle_count(), size_t(2 * n * n));
  for (const glm::uvec4& t : plane.triangles) {
    const glm::vec3 a(plane.positions[t.x]), b(plane.positions[t.y]), c(plane.positions[t.z]);
    const glm::vec3 normal = glm::normalize(glm::cross(b - a, c - a));
    EXPECT_NEAR(normal.y, 1.0f, 1e-6f);
  }
  const Bounds b = plane.bounds();
  EXPECT_EQ(b.lo, glm::vec3(-2.0f, 0.0f, -1.0f));
  EXPECT_EQ(b.hi, glm::vec3(2.0f, 0.0f, 1.0f));
  const MeshTopology e = mesh_topology(plane);
  EXPECT_EQ(e.boundary, size_t(4 * n));
  EXPECT_EQ(e.misoriented, 0u);
}

TEST(Generators, SubdivisionQuadruplesAndKeepsClosureAndVolume) {
  const TriangleSoup torus = make_torus();
  const double volume = signed_volume(torus);
  for (int levels = 1; levels <= 2; ++levels) {
    const TriangleSoup fine = subdivide_midpoint(torus, levels);
    EXPECT_EQ(fine.triangle_count(), torus.triangle_count() << (2 * levels));
    // Closed mesh: V' = V + E with E = 3T/2.
    EXPECT_EQ(fine.vertex_count(), levels == 1 ? 400u + 1200u : 1600u + 4800u);
    expect_closed_and_outward(fine, "subdivided torus");
    EXPECT_NEAR(signed_volume(fine) / volume, 1.0, 1e-5);
    EXPECT_EQ(fine.bounds().lo, torus.bounds().lo);
    EXPECT_EQ(fine.bounds().hi, torus.bounds().hi);
  }
  EXPECT_TRUE(same_soup(subdivide_midpoint(torus, 0), torus));
  // Material ids follow their parent triangle.
  const TriangleSoup tree = make_tree(0.2f, 1), fine_tree = subdivide_midpoint(tree, 1);
  for (size_t t = 0; t < tree.triangle_count(); ++t)
    for (size_t k = 0; k < 4; ++k) ASSERT_EQ(fine_tree.triangles[4 * t + k].w, tree.triangles[t].w);
  EXPECT_THROW(subdivide_midpoint(torus, -1), Error);
  EXPECT_THROW(subdivide_midpoint(torus, 14), Error);  // 800 * 4^14 > 2^31
}

TEST(Generators, SubdivisionScalesToMillionsOfTriangles) {
  // Bunny-sized input (69,660 triangles) times 16: 1.1 M triangles.
  const TriangleSoup sphere = make_uv_sphere(1.0f, 130, 270);
  const TriangleSoup fine = subdivide_midpoint(sphere, 2);
  EXPECT_EQ(fine.triangle_count(), sphere.triangle_count() * 16);
  EXPECT_EQ(fine.vertex_count(), sphere.vertex_count() + sphere.triangle_count() * 3 / 2 * 5);
}

TEST(Generators, DispatcherReadsParams) {
  EXPECT_EQ(make_generated("torus", nullptr, "s.json").triangle_count(), 800u);
  EXPECT_EQ(make_generated("torus", {{"rings", 10}, {"sides", 6}}, "s.json").triangle_count(), 120u);
  EXPECT_EQ(make_generated("sphere", {{"stacks", 4}, {"slices", 5}}, "s.json").triangle_count(), 30u);
  EXPECT_EQ(make_generated("box", {{"lo", {0, 0, 0}}, {"hi", {1, 2, 3}}}, "s.json").bounds().hi,
            glm::vec3(1, 2, 3));
  EXPECT_EQ(make_generated("plane", {{"size", {3, 1}}, {"subdivisions", 2}}, "s.json").triangle_count(), 8u);
  EXPECT_TRUE(
      same_soup(make_generated("tree", {{"density", 0.5}, {"seed", 9}}, "s.json"), make_tree(0.5f, 9)));
  FoliageParams f;
  f.size = glm::vec3(2.0f, 1.0f, 1.5f);
  f.leaves = 50;
  f.leaf_size = 0.2f;
  f.seed = 3;
  EXPECT_TRUE(same_soup(
      make_generated("foliage", {{"size", {2, 1, 1.5}}, {"leaves", 50}, {"leaf_size", 0.2}, {"seed", 3}},
                     "s.json"),
      make_foliage(f)));
  // Density is leaves per unit volume: 100 * (2 * 1 * 1.5) = 300 leaves.
  f.leaves = 300;
  EXPECT_TRUE(same_soup(
      make_generated("foliage", {{"size", {2, 1, 1.5}}, {"density", 100}, {"leaf_size", 0.2}, {"seed", 3}},
                     "s.json"),
      make_foliage(f)));
  EXPECT_TRUE(same_soup(make_generated("foliage", nullptr, "s.json"), make_foliage()));
  VaseParams p;
  p.profile = {0.4f, 0.3f, 0.35f};
  p.rows = 8;
  EXPECT_TRUE(same_soup(make_generated("vase", {{"profile", {0.4, 0.3, 0.35}}, {"rows", 8}}, "s.json"),
                        make_vase(p)));
}

std::string generated_error(const std::string& name, const nlohmann::json& params) {
  try {
    make_generated(name, params, "s.json", "meshes[2].params");
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(Generators, DispatcherErrorsNameTheKey) {
  EXPECT_EQ(generated_error("torus", {{"majr", 2}}),
            "s.json: unknown key 'meshes[2].params.majr' (did you mean 'meshes[2].params.major'?)");
  EXPECT_EQ(generated_error("cube", nullptr),
            "s.json: unknown generator 'cube' (known: torus, sphere, box, vase, tree, plane, foliage)");
  EXPECT_EQ(generated_error("torus", {{"rings", 2.5}}),
            "s.json: 'meshes[2].params.rings' must be an integer in [3, 4096] (got 2.5)");
  EXPECT_EQ(generated_error("torus", {{"minor", 1.5}}),
            "s.json: 'meshes[2].params.minor' must be smaller than 'major' (a ring torus) (got 1.5)");
  EXPECT_EQ(generated_error("sphere", {{"radius", "big"}}),
            "s.json: 'meshes[2].params.radius' must be a number (got \"big\")");
  EXPECT_EQ(generated_error("box", {{"lo", {1, 1}}}),
            "s.json: 'meshes[2].params.lo' must be an array of 3 numbers (got [1,1])");
  EXPECT_NE(generated_error("vase", {{"thickness", 0.5}}).find("'meshes[2].params.profile'"),
            std::string::npos);
  EXPECT_NE(generated_error("tree", {{"density", -1}}).find("'meshes[2].params.density'"), std::string::npos);
  EXPECT_EQ(generated_error("foliage", {{"leaf_sise", 0.1}}),
            "s.json: unknown key 'meshes[2].params.leaf_sise' (did you mean 'meshes[2].params.leaf_size'?)");
  EXPECT_EQ(generated_error("foliage", {{"leaves", 10}, {"density", 5}}),
            "s.json: 'meshes[2].params.density' cannot be given with 'leaves' (give one of them)");
  EXPECT_EQ(generated_error("foliage", {{"leaves", 1.5}}),
            "s.json: 'meshes[2].params.leaves' must be an integer in [0, 4194304] (got 1.5)");
  EXPECT_NE(generated_error("foliage", {{"density", -1}}).find("'meshes[2].params.density' must be >= 0"),
            std::string::npos);
  EXPECT_NE(generated_error("foliage", {{"density", 1e7}}).find("'meshes[2].params.density'"),
            std::string::npos);
  EXPECT_NE(generated_error("foliage", {{"size", {1, 0.1, 1}}, {"leaf_size", 0.1}})
                .find("'meshes[2].params.leaf_size' must be below 0.07155"),
            std::string::npos);
  EXPECT_NE(
      generated_error("foliage", {{"size", {1, -1, 1}}}).find("'meshes[2].params.size' must be positive"),
      std::string::npos);
  EXPECT_NE(generated_error("plane", 3).find("'meshes[2].params' must be an object"), std::string::npos);
}

}  // namespace
}  // namespace voxr
