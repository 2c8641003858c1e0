// eval/render_case.h: one scene made ready to render, the exact reference built on first need only.
#include <gtest/gtest.h>

#include "core/default_scene.h"
#include "eval/render_case.h"
#include "render/render_scene.h"
#include "util/error.h"

namespace voxr {
namespace {

TEST(RenderCase, PlacesTheSceneAtTheSizeAndBuildsTheReferenceOnFirstNeed) {
  const Scene scene = default_scene();
  RenderCase c(scene, 64, 48);
  EXPECT_EQ(c.camera().width, 64u);
  EXPECT_EQ(c.camera().height, 48u);
  Scene copy = scene;
  EXPECT_EQ(c.soup().triangle_count(), take_scene_triangles(copy).triangle_count());
  EXPECT_EQ(c.render_materials().size(), scene.materials.size());
  // The light as render_light places it: relative to the soup's anchor, ambient from the environment.
  const RenderLight expected = render_light(scene.light, c.environment().mean(), c.soup().anchor);
  for (int a = 0; a < 3; ++a) EXPECT_EQ(c.light().intensity[a], expected.intensity[a]);
  EXPECT_EQ(c.reference().build_ms(), 0.0);  // nothing asked yet: no BVH
  EXPECT_GT(c.reference().scene().build_ms(), 0.0);
}

TEST(RenderCase, EmptySizeOrSoupIsAnError) {
  EXPECT_THROW(RenderCase(default_scene(), 0, 48), Error);
  Scene empty = default_scene();
  empty.meshes.clear();
  EXPECT_THROW(RenderCase(empty, 64, 48), Error);
}

}  // namespace
}  // namespace voxr
