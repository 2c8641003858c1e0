// Render regression tests (tests/render_regression.h): small images of the shadow and refraction scenes by
// every method,
// against references stored in tests/render_references/ (regenerate on purpose with
// VOXR_UPDATE_REFERENCES=1). Each test states its tolerance: the kernels are deterministic on one device;
// the slack is for other devices' float rounding.
#include <gtest/gtest.h>

#include <string>

#include "core/default_scene.h"
#include "core/scene.h"
#include "reference/embree_reference.h"
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
  EmbreeReference reference(soup, materials);  // the reference shadows ask it
  renderer.set_scene(soup, materials, &reference);
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

TEST(ShadowImages, DefaultSceneVoxelExactShadows) {
  EXPECT_TRUE(test::matches_reference(render_small(default_scene(), ShadowMethod::kVoxelExact, 128),
                                      "default_voxel_exact_128", {0.005, 0.05, 0.005}));
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

TEST(ShadowImages, DefaultSceneExactAndNone) {
  const Scene scene = default_scene();
  EXPECT_TRUE(test::matches_reference(render_small(scene, ShadowMethod::kReference, 128), "default_reference",
                                      {0.005, 0.05, 0.005}));
  EXPECT_TRUE(test::matches_reference(render_small(scene, ShadowMethod::kNone, 128), "default_none",
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

// The refraction scene with a figure inside a glass ball, 96 x 72, voxel shadows at 64, by `method` (grid
// `res` for the voxel methods); the references through Embree.
ImageRgba render_refraction(RefractionMethod method, uint32_t res = 128, StepRule step = StepRule::kDda,
                            NormalKind normals = NormalKind::kSmooth) {
  Scene scene = scene_file("ball-figure.json");
  const std::vector<Material> materials = scene.materials;
  const EnvironmentMap environment = make_environment_map(scene.environment);
  const TriangleSoup soup = take_scene_triangles(scene);
  const CameraFrame camera = make_camera_frame(scene.camera, soup.anchor, soup.bounds(), 96, 72);
  const RenderLight light = render_light(scene.light, environment.mean(), soup.anchor);
  FrameRenderer renderer(test::runtime());
  EmbreeReference reference(soup, materials);
  renderer.set_scene(soup, materials, &reference);
  renderer.set_environment(environment);
  RenderOptions o;
  // The references trace their own exact shadows.
  o.shadows = is_reference_refraction(method) ? ShadowMethod::kReference : ShadowMethod::kVoxel;
  o.shadow_resolution = 64;
  o.refraction.method = method;
  o.refraction.resolution = res;
  o.refraction.step = step;
  o.refraction.normals = normals;
  renderer.prepare(o);
  return renderer.render(light, camera, o).image;
}

TEST(RefractionImages, VoxelMultiBothStepRulesAndNormals) {
  EXPECT_TRUE(test::matches_reference(render_refraction(RefractionMethod::kVoxelMulti),
                                      "ball_figure_multi_dda_smooth", {0.005, 0.05, 0.005}));
  EXPECT_TRUE(test::matches_reference(
      render_refraction(RefractionMethod::kVoxelMulti, 128, StepRule::kPapers, NormalKind::kVoxel),
      "ball_figure_multi_papers_voxel", {0.005, 0.05, 0.005}));
}

TEST(RefractionImages, VoxelTwoAndImageSpace) {
  EXPECT_TRUE(test::matches_reference(render_refraction(RefractionMethod::kVoxelTwo), "ball_figure_two",
                                      {0.005, 0.05, 0.005}));
  EXPECT_TRUE(test::matches_reference(render_refraction(RefractionMethod::kImageSpace),
                                      "ball_figure_image_space", {0.005, 0.05, 0.005}));
}

// voxel-exact at a coarse grid: the exact triangles, so the image is the matched reference's.
TEST(RefractionImages, VoxelExact) {
  EXPECT_TRUE(test::matches_reference(render_refraction(RefractionMethod::kVoxelExact, 32),
                                      "ball_figure_exact", {0.005, 0.05, 0.005}));
}

TEST(RefractionImages, DistanceMapsAndNone) {
  EXPECT_TRUE(test::matches_reference(render_refraction(RefractionMethod::kDistanceMaps),
                                      "ball_figure_distance_maps", {0.005, 0.05, 0.005}));
  EXPECT_TRUE(test::matches_reference(render_refraction(RefractionMethod::kNone), "ball_figure_none",
                                      {0.005, 0.05, 0.005}));
}

TEST(RefractionImages, References) {
  EXPECT_TRUE(test::matches_reference(render_refraction(RefractionMethod::kReference),
                                      "ball_figure_reference", {0.005, 0.05, 0.005}));
  EXPECT_TRUE(test::matches_reference(render_refraction(RefractionMethod::kReferenceFull),
                                      "ball_figure_reference_full", {0.005, 0.05, 0.005}));
}

}  // namespace
}  // namespace voxr
