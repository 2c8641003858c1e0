// Render regression tests (tests/render_regression.h): small images of the shadow scenes by every method,
// against references stored in tests/render_references/ (regenerate on purpose with
// VOXR_UPDATE_REFERENCES=1). Each test states its tolerance: the kernels are deterministic on one device;
// the slack is for other devices' float rounding.
#include <gtest/gtest.h>

#include <string>

#include "core/default_scene.h"
#include "core/scene.h"
#include "render/environment_map.h"
#include "render/frame_renderer.h"
#include "render/render_scene.h"
#include "render_regression.h"
#include "test_support.h"

namespace voxr {
namespace {

ImageRgba render_small(const Scene& source, ShadowMethod method, uint32_t res,
                       RasterMode mode = RasterMode::kCenter) {
  Scene scene = source;
  const std::vector<Material> materials = scene.materials;
  const TriangleSoup soup = take_scene_triangles(scene);
  FrameRenderer renderer(test::runtime());
  renderer.set_scene(soup, materials);
  RenderOptions o;
  o.shadows = method;
  o.shadow_resolution = res;
  o.mode = mode;
  renderer.prepare(o);
  const CameraFrame camera = make_camera_frame(scene.camera, soup.anchor, soup.bounds(), 96, 72);
  return renderer
      .render(render_light(scene.light, make_environment_map(scene.environment).mean(), soup.anchor), camera,
              o)
      .image;
}

Scene scene_file(const std::string& name) {
  return load_scene(std::string(VOXR_SOURCE_DIR) + "/data/scenes/" + name);
}

TEST(ShadowImages, DefaultSceneVoxelShadows) {
  EXPECT_TRUE(test::matches_reference(render_small(default_scene(), ShadowMethod::kVoxel, 128),
                                      "default_voxel_128", {0.005, 0.05, 0.005}));
}

TEST(ShadowImages, DefaultSceneBaselines) {
  const Scene scene = default_scene();
  EXPECT_TRUE(test::matches_reference(render_small(scene, ShadowMethod::kUniform, 128), "default_uniform_128",
                                      {0.005, 0.05, 0.005}));
  EXPECT_TRUE(test::matches_reference(render_small(scene, ShadowMethod::kFilter, 128), "default_filter_128",
                                      {0.005, 0.05, 0.005}));
  EXPECT_TRUE(test::matches_reference(render_small(scene, ShadowMethod::kOpaque, 128), "default_opaque_128",
                                      {0.005, 0.05, 0.005}));
}

TEST(ShadowImages, GlassOverAFloorColouredShadows) {
  EXPECT_TRUE(test::matches_reference(render_small(scene_file("glass-floor.json"), ShadowMethod::kVoxel, 128),
                                      "glass_floor_voxel_128", {0.005, 0.05, 0.005}));
}

TEST(ShadowImages, FoliageConservativeMode) {
  EXPECT_TRUE(test::matches_reference(
      render_small(scene_file("foliage.json"), ShadowMethod::kVoxel, 128, RasterMode::kConservative),
      "foliage_voxel_conservative_128", {0.005, 0.05, 0.005}));
}

}  // namespace
}  // namespace voxr
