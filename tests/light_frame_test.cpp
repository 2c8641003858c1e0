// The light's grid: fitted to the casters that can shadow a visible receiver, orthographic for directional
// lights and a frustum in projective space for point lights, with clear errors where a frustum cannot work.
#include <gtest/gtest.h>

#include <cmath>

#include "render/light_frame.h"
#include "render/render_scene.h"
#include "test_lights.h"
#include "test_support.h"

namespace voxr {
namespace {

TEST(LightFrame, AFloorUnderEverythingCastsNothingSoTheGridFitsTheLeaf) {
  TriangleSoup soup;
  test::add_square(soup, 0.0f, -10.0f, 10.0f, 0);  // a 20 x 20 floor
  test::add_square(soup, 1.0f, -0.5f, 0.5f, 1);    // a 1 x 1 leaf
  const LightFrame f = fit_light_frame(test::directional_light({0, -1, 0}), soup.bounds(), soup, 64);
  EXPECT_FALSE(f.projective());
  // 62 columns over the leaf's metre and one of margin each side: the floor's 20 m would need 0.32 m voxels.
  EXPECT_NEAR(f.grid.voxel_size, 1.0f / 62.0f, 1e-4f);
  EXPECT_EQ(f.grid.dims.x, 64u);
  EXPECT_EQ(f.grid.dims.y, 64u);
  // The leaf's centre is mid-grid; the floor below it lies beyond the last slab.
  const glm::vec3 leaf = f.to_grid({0, 1, 0}), floor = f.to_grid({0, 0, 0});
  EXPECT_NEAR(leaf.x, 32.0f, 0.01f);
  EXPECT_NEAR(leaf.y, 32.0f, 0.01f);
  EXPECT_GT(floor.z, leaf.z + 60.0f);
  EXPECT_NE(f.describe().find("orthographic 64 x 64"), std::string::npos) << f.describe();
}

TEST(LightFrame, PointLightFrustumIsProjectiveWithDepthSlices) {
  TriangleSoup soup;
  test::add_square(soup, 0.0f, -10.0f, 10.0f, 0);
  test::add_square(soup, 1.0f, -0.5f, 0.5f, 1);
  const LightFrame f = fit_light_frame(test::point_light({0, 5, 0}), soup.bounds(), soup, 64);
  ASSERT_TRUE(f.projective());
  EXPECT_EQ(f.grid.dims.z, 64u);
  // The nearest caster (the leaf, 4 below the light) starts the first slab; slabs are uniform in 1/depth.
  EXPECT_NEAR(f.near_depth, 4.0f, 0.01f);
  EXPECT_NEAR(f.to_grid({0, 1, 0}).z, 0.0f, 0.5f);
  const float mid = 1.0f / (0.5f / f.near_depth + 0.5f / f.far_depth);  // depth halfway in 1/z
  EXPECT_NEAR(f.to_grid({0, 5 - mid, 0}).z, 32.0f, 0.01f);
  // A point straight below the light projects to the column under the light, whatever its depth.
  EXPECT_NEAR(f.to_grid({0, 0, 0}).x, f.to_grid({0, 1, 0}).x, 1e-3f);
  // project_to_light_grid maps positions as to_grid does.
  const TriangleSoup projected = project_to_light_grid(soup, f);
  ASSERT_FALSE(projected.triangles.empty());
  for (const glm::uvec4& t : projected.triangles)
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(projected.positions[t[c]].x));
}

TEST(LightFrame, TrianglesBehindAPointLightAreClippedAway) {
  TriangleSoup soup;
  test::add_square(soup, 0.0f, -2.0f, 2.0f, 0);
  test::add_square(soup, 1.0f, -0.5f, 0.5f, 1);
  // A wall through the light's plane: half of it behind the light.
  const uint32_t b = uint32_t(soup.positions.size());
  soup.positions.push_back({1.0f, -1.0f, -1.0f, 1});
  soup.positions.push_back({1.0f, 9.0f, -1.0f, 1});
  soup.positions.push_back({1.0f, 9.0f, 1.0f, 1});
  soup.triangles.push_back({b, b + 1, b + 2, 1});
  Bounds receivers;
  receivers.extend({-2, 0, -2});
  receivers.extend({2, 1, 2});
  const LightFrame f = fit_light_frame(test::point_light({0, 5, 0}), receivers, soup, 32);
  const TriangleSoup projected = project_to_light_grid(soup, f);
  for (size_t v = 0; v < projected.positions.size(); ++v)
    EXPECT_TRUE(std::isfinite(projected.positions[v].z) && projected.positions[v].z > -1e6f) << v;
}

TEST(LightFrame, APointLightAmongTheReceiversIsAClearError) {
  TriangleSoup soup;
  test::add_square(soup, 0.0f, -2.0f, 2.0f, 0);
  test::add_square(soup, 3.0f, -2.0f, 2.0f, 0);
  try {
    fit_light_frame(test::point_light({0, 1, 0}), soup.bounds(), soup, 32);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("lies among the receivers"), std::string::npos) << e.what();
  }
  EXPECT_THROW(fit_light_frame(test::directional_light({0, -1, 0}), soup.bounds(), soup, 1), Error);
}

}  // namespace
}  // namespace voxr
