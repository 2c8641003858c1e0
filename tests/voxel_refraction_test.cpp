// Voxel refraction (render/voxel_refraction.h, Chang & Lai TR 1688 §5 and PG 2011 §5) in whole frames: the
// analytic centre ray through a glass ball with every step rule and normal kind, both methods; voxel-two
// never meets more than two interfaces; total internal reflection in a gem; no NaN on any refraction scene;
// pixels that see no glass are as without refraction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/generators.h"
#include "core/scene.h"
#include "refraction_ball.h"
#include "render/environment_map.h"
#include "render/frame_renderer.h"
#include "render/render_scene.h"
#include "test_support.h"

namespace voxr {
namespace {

using namespace test::ball;

RenderOptions options(RefractionMethod method, StepRule step, NormalKind normals, uint32_t res = 256) {
  RenderOptions o;
  o.shadows = ShadowMethod::kNone;
  o.keep_samples = true;
  o.refraction.method = method;
  o.refraction.step = step;
  o.refraction.normals = normals;
  o.refraction.resolution = res;
  return o;
}

TEST(VoxelRefraction, BallCentreRayMatchesTheAnalyticTransmittance) {
  const TriangleSoup soup = scene(false);
  FrameRenderer renderer(test::runtime());
  renderer.set_scene(soup, materials());
  renderer.set_environment(EnvironmentMap::checker());
  const float r0 = (kIor - 1.0f) / (kIor + 1.0f), f = r0 * r0;
  for (RefractionMethod method : {RefractionMethod::kVoxelMulti, RefractionMethod::kVoxelTwo})
    for (StepRule step : {StepRule::kDda, StepRule::kPapers})
      for (NormalKind normals : {NormalKind::kVoxel, NormalKind::kSmooth}) {
        SCOPED_TRACE(std::string(refraction_method_info(method).name) + " " + step_rule_info(step).name +
                     " " + normal_kind_info(normals).name);
        const RenderOptions o = options(method, step, normals);
        renderer.prepare(o);
        const RenderedFrame frame = renderer.render(light(), camera(), o);
        expect_all_finite(frame);
        const RefractionPath& path = frame.paths[centre_pixel()];
        EXPECT_EQ(path.events & VOXR_PATH_EVENTS_MASK, 2u);
        EXPECT_TRUE(path.events & VOXR_PATH_ENV);
        EXPECT_EQ(path.events & (VOXR_PATH_TIR | VOXR_PATH_LOST), 0u);
        const float angle = glm::degrees(
            std::acos(std::min(1.0f, glm::dot(glm::normalize(vec(path.exit_direction)), camera().forward))));
        EXPECT_LT(angle, 1.0f);
        EXPECT_NEAR(path.exit_position[2], -kRadius, 2.0f / 256.0f * 2.0f);  // within two voxels
        EXPECT_NEAR(path.fresnel, f, 1e-4f);
        // The target: within 1 % at grid 256 (the march's thickness is exact to a voxel, 2/256 of
        // the 2-unit chord, and absorbs at most 0.2 x 2/256).
        for (int c = 0; c < 3; ++c) {
          const float expected = (1.0f - f) * (1.0f - f) * std::exp(-kAbsorption[c] * 2.0f * kRadius);
          EXPECT_NEAR(path.throughput[c], expected, 0.01f * expected) << "channel " << c;
        }
      }
}

TEST(VoxelRefraction, PixelsWithoutGlassAreAsWithoutRefraction) {
  const TriangleSoup soup = scene(true);
  FrameRenderer renderer(test::runtime());
  renderer.set_scene(soup, materials());
  renderer.set_environment(EnvironmentMap::checker());
  RenderOptions none = options(RefractionMethod::kNone, StepRule::kDda, NormalKind::kSmooth);
  renderer.prepare(none);
  const RenderedFrame plain = renderer.render(light(), camera(), none);
  const RenderOptions multi =
      options(RefractionMethod::kVoxelMulti, StepRule::kDda, NormalKind::kSmooth, 128);
  renderer.prepare(multi);
  const RenderedFrame refracted = renderer.render(light(), camera(), multi);
  size_t glass = 0, box_ends = 0;
  for (size_t i = 0; i < plain.samples.size(); ++i) {
    const bool sees_glass =
        plain.samples[i].triangle != VOXR_NO_TRIANGLE && plain.samples[i].material == kGlass;
    if (sees_glass) {
      ++glass;
      box_ends += refracted.samples[i].triangle == VOXR_VOXEL_HIT && refracted.samples[i].material == kBox;
      continue;
    }
    EXPECT_EQ(plain.image.pixels[i], refracted.image.pixels[i]) << "pixel " << i;
    EXPECT_EQ(refracted.paths[i].events, 0u);
  }
  EXPECT_GT(glass, 100u);
  // The slab behind the ball fills the view through it: most refracted paths end on it.
  EXPECT_GT(box_ends, glass * 3 / 4);
}

TEST(VoxelRefraction, TiltedSlabShiftsTheRayByTheTextbookOffset) {
  // A glass slab 0.5 thick (a make_box: its faces must shade flat for the exact front refraction), turned 40
  // degrees about y: the centre ray leaves parallel to itself, shifted sideways by t sin(theta - theta_t) /
  // cos(theta_t).
  const float t = 0.5f, theta = glm::radians(40.0f);
  TriangleSoup soup;
  const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), theta, glm::vec3(0.0f, 1.0f, 0.0f));
  soup.append(make_box(glm::vec3(-1.0f, -1.0f, -t / 2), glm::vec3(1.0f, 1.0f, t / 2)), turn, kGlass);
  FrameRenderer renderer(test::runtime());
  renderer.set_scene(soup, materials());
  const float theta_t = std::asin(std::sin(theta) / kIor);
  const float expected = t * std::sin(theta - theta_t) / std::cos(theta_t);
  for (RefractionMethod method : {RefractionMethod::kVoxelMulti, RefractionMethod::kVoxelTwo})
    for (StepRule step : {StepRule::kDda, StepRule::kPapers}) {
      SCOPED_TRACE(std::string(refraction_method_info(method).name) + " " + step_rule_info(step).name);
      const RenderOptions o = options(method, step, NormalKind::kVoxel);
      renderer.prepare(o);
      const RenderedFrame frame = renderer.render(light(), camera(), o);
      const RefractionPath& path = frame.paths[centre_pixel()];
      ASSERT_EQ(path.events & VOXR_PATH_EVENTS_MASK, 2u);
      const glm::vec3 v = camera().forward;
      EXPECT_LT(glm::degrees(std::acos(std::min(1.0f, glm::dot(vec(path.exit_direction), v)))), 0.5f);
      const glm::vec3 q = vec(path.exit_position) - camera().eye;
      const float offset = glm::length(q - glm::dot(q, v) * v);
      const float voxel = 2.0f * std::cos(theta) + t * std::sin(theta);          // the slab's x extent...
      EXPECT_NEAR(offset, expected, voxel / 256.0f) << "textbook " << expected;  // ...over 256 voxels
    }
}

Scene scene_file(const std::string& name) {
  return load_scene(std::string(VOXR_SOURCE_DIR) + "/data/scenes/" + name);
}

struct SceneFrame {
  RenderedFrame frame;
  size_t glass_pixels = 0;
};

SceneFrame render_scene_file(const std::string& name, const RenderOptions& o) {
  Scene scene = scene_file(name);
  const std::vector<Material> mats = scene.materials;
  const EnvironmentMap environment = make_environment_map(scene.environment);
  const TriangleSoup soup = take_scene_triangles(scene);
  FrameRenderer renderer(test::runtime());
  renderer.set_scene(soup, mats);
  renderer.set_environment(environment);
  renderer.prepare(o);
  const CameraFrame camera = make_camera_frame(scene.camera, soup.anchor, soup.bounds(), 80, 60);
  SceneFrame out;
  out.frame = renderer.render(render_light(scene.light, environment.mean(), soup.anchor), camera, o);
  for (const RefractionPath& p : out.frame.paths) out.glass_pixels += (p.events & VOXR_PATH_EVENTS_MASK) > 0;
  return out;
}

TEST(VoxelRefraction, EveryRefractionSceneRendersFiniteWithShadows) {
  for (const char* name : {"glass-sphere.json", "bunny-glass-130.json", "glass-vase.json", "ball-figure.json",
                           "gem.json", "thin-shell.json", "sphere-nearby.json", "default.json"})
    for (RefractionMethod method : {RefractionMethod::kVoxelMulti, RefractionMethod::kVoxelTwo}) {
      SCOPED_TRACE(std::string(name) + " " + refraction_method_info(method).name);
      RenderOptions o = options(method, StepRule::kDda, NormalKind::kSmooth, 96);
      o.shadows = ShadowMethod::kVoxel;
      o.shadow_resolution = 64;
      const SceneFrame s = render_scene_file(name, o);
      expect_all_finite(s.frame);
      for (const glm::vec4& p : s.frame.image.pixels) ASSERT_GE(std::min({p.x, p.y, p.z}), 0.0f);
      EXPECT_GT(s.glass_pixels, 50u);
      if (method == RefractionMethod::kVoxelTwo) {
        for (const RefractionPath& p : s.frame.paths) ASSERT_LE(p.events & VOXR_PATH_EVENTS_MASK, 2u);
      }
    }
}

TEST(VoxelRefraction, GemReflectsTotallyInside) {
  const SceneFrame s = render_scene_file(
      "gem.json", options(RefractionMethod::kVoxelMulti, StepRule::kDda, NormalKind::kSmooth));
  size_t tir = 0, many = 0;
  for (const RefractionPath& p : s.frame.paths) {
    tir += (p.events & VOXR_PATH_TIR) != 0;
    many += (p.events & VOXR_PATH_EVENTS_MASK) > 2;
  }
  // Diamond's critical angle is 24.4 degrees: a good share of the rays that enter reflect inside.
  EXPECT_GT(tir, s.glass_pixels / 5);
  EXPECT_GT(many, s.glass_pixels / 5);
}

}  // namespace
}  // namespace voxr
