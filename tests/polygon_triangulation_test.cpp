// Polygon faces -> triangles (mesh/polygon_triangulation.h): a concave polygon is covered exactly (the
// triangles' areas add up to the polygon's, none lies outside it, all keep its winding), convex ones are
// fanned as before, and faces with no single right answer are counted for a warning.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "core/mesh_loader.h"
#include "mesh/polygon_triangulation.h"
#include "test_support.h"

namespace voxr {
namespace {

// One face of `corners` 2-D points placed on a plane by `place` (rotation and translation).
PolygonMesh polygon(const std::vector<glm::dvec2>& corners, const glm::dmat4& place = glm::dmat4(1.0)) {
  PolygonMesh mesh;
  std::vector<uint32_t> ids;
  for (const glm::dvec2& c : corners) {
    ids.push_back(uint32_t(mesh.positions.size()));
    mesh.positions.push_back(glm::dvec3(place * glm::dvec4(c, 0.0, 1.0)));
  }
  mesh.add_face(ids.data(), uint32_t(ids.size()));
  return mesh;
}

double shoelace(const std::vector<glm::dvec2>& p) {
  double a = 0.0;
  for (size_t i = 0; i < p.size(); ++i)
    a += p[i].x * p[(i + 1) % p.size()].y - p[(i + 1) % p.size()].x * p[i].y;
  return 0.5 * a;
}

bool inside(const std::vector<glm::dvec2>& p, glm::dvec2 q) {
  bool in = false;
  for (size_t i = 0, j = p.size() - 1; i < p.size(); j = i++)
    if ((p[i].y > q.y) != (p[j].y > q.y) &&
        q.x < (p[j].x - p[i].x) * (q.y - p[i].y) / (p[j].y - p[i].y) + p[i].x)
      in = !in;
  return in;
}

// The triangles of a simple counter-clockwise polygon cover it exactly: areas add up, every triangle is
// counter-clockwise (the face's winding) and its centroid lies inside the polygon.
void expect_exact_cover(const std::vector<glm::dvec2>& corners, const glm::dmat4& place,
                        const std::string& what) {
  SCOPED_TRACE(what);
  const PolygonMesh mesh = polygon(corners, place);
  HostArray<glm::uvec4> triangles;
  TriangulationReport report;
  triangulate(mesh, triangles, report);
  EXPECT_EQ(report.self_intersecting, 0u);
  EXPECT_EQ(report.nonplanar, 0u);
  ASSERT_EQ(triangles.size(), corners.size() - 2);
  double area = 0.0;
  for (const glm::uvec4& t : triangles) {
    const glm::dvec2 a = corners[t.x], b = corners[t.y], c = corners[t.z];
    const double signed_area = 0.5 * ((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
    EXPECT_GT(signed_area, 0.0) << "triangle " << t.x << " " << t.y << " " << t.z << " is reversed or flat";
    EXPECT_TRUE(inside(corners, (a + b + c) / 3.0)) << "triangle " << t.x << " " << t.y << " " << t.z;
    area += signed_area;
  }
  EXPECT_NEAR(area, shoelace(corners), 1e-9 * std::abs(shoelace(corners)));
}

// A random star-shaped polygon: corners at sorted angles with random radii (simple, mostly concave).
std::vector<glm::dvec2> random_star(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> radius(0.2, 1.0), jitter(0.0, 1.0);
  std::vector<double> angles(n);
  for (int i = 0; i < n; ++i) angles[i] = 2.0 * M_PI * (i + 0.8 * jitter(rng)) / n;
  std::vector<glm::dvec2> p;
  for (double a : angles) p.push_back(radius(rng) * glm::dvec2(std::cos(a), std::sin(a)));
  return p;
}

TEST(PolygonTriangulation, ConcavePolygonsAreCoveredExactly) {
  expect_exact_cover({{3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}, {0, 0}}, glm::dmat4(1.0), "L (case c19's cap)");
  expect_exact_cover({{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}}, glm::dmat4(1.0), "U");
  std::vector<glm::dvec2> comb{{0, 0}, {10, 0}};
  for (int k = 9; k >= 1; --k) comb.insert(comb.end(), {{double(k) + 0.5, 3.0}, {double(k), 1.0}});
  comb.push_back({0, 3});
  expect_exact_cover(comb, glm::dmat4(1.0), "comb");
  // Collinear corners along the notch.
  expect_exact_cover({{4, 0}, {4, 1}, {3, 1}, {2, 1}, {1, 1}, {1, 2}, {1, 3}, {0, 3}, {0, 0}},
                     glm::dmat4(1.0), "L with collinear corners");
  std::mt19937 rng(7);
  for (int i = 0; i < 200; ++i) {
    const std::vector<glm::dvec2> star = random_star(rng, 4 + i % 29);
    // On a random plane, a million units from the origin.
    glm::dmat4 place = glm::translate(glm::dmat4(1.0), glm::dvec3(1e6, -2e6, 5e5));
    place = glm::rotate(place, double(i) * 0.37, glm::normalize(glm::dvec3(1.0 + i % 3, 2.0, -1.0 + i % 5)));
    expect_exact_cover(star, place, "random star " + std::to_string(i));
  }
}

TEST(PolygonTriangulation, LargePolygonsStayExactAndFast) {
  // Above 256 corners crossings are left to CGAL's insertion (the pairwise test is quadratic).
  std::mt19937 rng(9);
  const std::vector<glm::dvec2> star = random_star(rng, 5000);
  expect_exact_cover(star, glm::dmat4(1.0), "5000-corner star");
  std::vector<glm::dvec2> crossing = star;
  std::swap(crossing[10], crossing[2500]);  // two long edges across the star
  HostArray<glm::uvec4> triangles;
  TriangulationReport report;
  triangulate(polygon(crossing), triangles, report);
  EXPECT_EQ(report.self_intersecting, 1u);
  EXPECT_EQ(triangles.size(), crossing.size() - 2);
  std::vector<glm::dvec2> repeated = star;
  repeated[3000] = repeated[100];  // a corner twice: fanned, not indices lost
  triangles.clear();
  triangulate(polygon(repeated), triangles, report);
  EXPECT_EQ(report.self_intersecting, 2u);
  for (const glm::uvec4& t : triangles) EXPECT_LT(std::max({t.x, t.y, t.z}), repeated.size());
}

TEST(PolygonTriangulation, ConvexPolygonsAreFannedFromTheirFirstCorner) {
  std::vector<glm::dvec2> hexagon;
  for (int k = 0; k < 6; ++k) hexagon.push_back({std::cos(k * M_PI / 3), std::sin(k * M_PI / 3)});
  HostArray<glm::uvec4> triangles;
  TriangulationReport report;
  triangulate(polygon(hexagon), triangles, report);
  HostArray<glm::uvec4> fan;
  for (uint32_t k = 1; k + 1 < 6; ++k) fan.push_back({0, k, k + 1, 0});
  EXPECT_EQ(triangles, fan);
  EXPECT_EQ(report.polygons, 1u);
  EXPECT_EQ(report.concave, 0u);
}

TEST(PolygonTriangulation, AmbiguousFacesAreCountedForAWarning) {
  PolygonMesh mesh = polygon({{0, 0}, {1, 0}, {1, 1}, {0, 1}});  // face 0: planar square
  mesh.positions[2].z = 0.5;                                     // ... now twisted: not planar
  const PolygonMesh bow_tie = polygon({{0, 0}, {1, 1}, {1, 0}, {0, 1}});
  for (size_t i = 0; i < 4; ++i) mesh.positions.push_back(bow_tie.positions[i]);
  const uint32_t crossing[4] = {4, 5, 6, 7}, segment[2] = {0, 1};
  mesh.add_face(crossing, 4);  // face 1: crosses itself
  mesh.add_face(segment, 2);   // face 2: no area
  HostArray<glm::uvec4> triangles;
  TriangulationReport report;
  triangulate(mesh, triangles, report);
  EXPECT_EQ(report.nonplanar, 1u);
  EXPECT_EQ(report.first_nonplanar, 0u);
  EXPECT_EQ(report.self_intersecting, 1u);
  EXPECT_EQ(report.first_self_intersecting, 1u);
  EXPECT_EQ(report.too_small, 1u);
  EXPECT_EQ(triangles.size(), 4u);  // both quads as two triangles each
  const std::vector<std::string> warnings = report.warnings("m.obj");
  ASSERT_EQ(warnings.size(), 3u);
  EXPECT_EQ(warnings[0].rfind("m.obj: 1 polygon faces are not planar (first: face 0)", 0), 0u) << warnings[0];
  EXPECT_EQ(warnings[1].rfind("m.obj: 1 polygon faces cross themselves", 0), 0u) << warnings[1];
  EXPECT_EQ(warnings[2], "m.obj: 1 faces have fewer than 3 corners and were dropped");
}

TEST(PolygonTriangulation, LoadMeshPassesTheWarningsOn) {
  test::TempDir dir;
  std::vector<std::string> warnings;
  const TriangleSoup soup =
      load_mesh(dir.write("twisted.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0.5\nv 0 1 0\nf 1 2 3 4\n"), &warnings);
  EXPECT_EQ(soup.triangles.size(), 2u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("twisted.obj: 1 polygon faces are not planar"), std::string::npos)
      << warnings[0];
}

}  // namespace
}  // namespace voxr
