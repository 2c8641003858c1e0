// Angle-weighted vertex normals (render/vertex_normals.h).
#include <gtest/gtest.h>

#include "core/generators.h"
#include "render/vertex_normals.h"

namespace voxr {
namespace {

void expect_near(glm::vec3 a, glm::vec3 b, float tol = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TEST(VertexNormals, FlatPlaneIsUp) {
  const TriangleSoup plane = make_plane(glm::vec2(2.0f, 3.0f), 5);
  const std::vector<glm::vec3> n = vertex_normals(plane);
  ASSERT_EQ(n.size(), plane.positions.size());
  for (const glm::vec3& v : n) expect_near(v, glm::vec3(0, 1, 0));
}

TEST(VertexNormals, CubeCornerIsTheAngleWeightedAverage) {
  // Each face meets a corner at 90 degrees whether one or two of its triangles use the corner, so every
  // corner's normal is the diagonal (an area or count weighting would lean towards the split faces).
  const TriangleSoup box = make_box(glm::vec3(-1.0f), glm::vec3(1.0f));
  const std::vector<glm::vec3> n = vertex_normals(box);
  ASSERT_EQ(n.size(), 8u);
  for (size_t v = 0; v < n.size(); ++v) expect_near(n[v], glm::normalize(glm::vec3(box.positions[v])));
}

TEST(VertexNormals, ZeroAreaTrianglesIgnoredUnusedVerticesUp) {
  TriangleSoup soup;
  soup.positions = {glm::vec4(0, 0, 0, 1), glm::vec4(1, 0, 0, 1), glm::vec4(0, 1, 0, 1),
                    glm::vec4(2, 0, 0, 1), glm::vec4(5, 5, 5, 1)};
  soup.triangles = {{0, 2, 1, 0}, {0, 1, 3, 0}};  // the second is a segment
  const std::vector<glm::vec3> n = vertex_normals(soup);
  expect_near(n[0], glm::vec3(0, 0, -1));
  expect_near(n[1], glm::vec3(0, 0, -1));
  expect_near(n[3], glm::vec3(0, 0, 1));  // only on the zero-area triangle
  expect_near(n[4], glm::vec3(0, 0, 1));  // unused
}

}  // namespace
}  // namespace voxr
