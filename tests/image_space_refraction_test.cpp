// Image-space refraction (render/image_space_refraction.h, Wyman 2005) in whole frames: a glass ball's
// centre pixel passes straight through with two refractions, (1 - F)^2 and Beer-Lambert over the diameter; an
// opaque box behind the ball is found through it by the nearby-geometry lookup; pixels that see no glass are
// the same as without refraction; no pixel is NaN.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/generators.h"
#include "core/material.h"
#include "refraction_ball.h"
#include "render/environment_map.h"
#include "render/frame_renderer.h"
#include "test_support.h"

namespace voxr {
namespace {

using namespace test::ball;

RenderOptions options(RefractionMethod method) {
  RenderOptions o;
  o.shadows = ShadowMethod::kNone;
  o.keep_samples = true;
  o.refraction.method = method;
  return o;
}

struct Rendered {
  RenderedFrame image_space, none;
};

Rendered render(const TriangleSoup& soup, const EnvironmentMap& environment) {
  FrameRenderer renderer(test::runtime());
  FixedInwardDistances d_n(inward_distances(soup));
  renderer.set_scene(soup, materials(), &d_n);
  renderer.set_environment(environment);
  Rendered out;
  for (RefractionMethod m : {RefractionMethod::kImageSpace, RefractionMethod::kNone}) {
    const RenderOptions o = options(m);
    renderer.prepare(o);
    (m == RefractionMethod::kNone ? out.none : out.image_space) = renderer.render(light(), camera(), o);
  }
  return out;
}

TEST(ImageSpaceRefraction, BallCentrePassesStraightThroughWithTwoRefractions) {
  const TriangleSoup soup = scene(false);
  const Rendered r = render(soup, EnvironmentMap::checker());
  ASSERT_EQ(r.image_space.paths.size(), size_t(kWidth) * kHeight);
  expect_all_finite(r.image_space);
  const RefractionPath& path = r.image_space.paths[centre_pixel()];
  const SurfaceSample& end = r.image_space.samples[centre_pixel()];
  EXPECT_EQ(path.events & VOXR_PATH_EVENTS_MASK, 2u);
  EXPECT_EQ(path.events & (VOXR_PATH_TIR | VOXR_PATH_LOST), 0u);
  EXPECT_TRUE(path.events & VOXR_PATH_ENV);
  EXPECT_EQ(end.triangle, VOXR_NO_TRIANGLE);
  const glm::vec3 view = camera().forward;
  const float angle =
      glm::degrees(std::acos(std::min(1.0f, glm::dot(glm::normalize(vec(path.exit_direction)), view))));
  EXPECT_LT(angle, 1.0f) << "the exit direction turned from the view direction";
  // The exit point lies on the far side of the ball.
  EXPECT_NEAR(path.exit_position[2], -kRadius, 0.02f);
  const float r0 = (kIor - 1.0f) / (kIor + 1.0f);
  const float f = r0 * r0;  // Schlick at normal incidence, both ways
  EXPECT_NEAR(path.fresnel, f, 1e-3f);
  for (int c = 0; c < 3; ++c) {
    const float expected = (1.0f - f) * (1.0f - f) * std::exp(-kAbsorption[c] * 2.0f * kRadius);
    EXPECT_NEAR(path.throughput[c], expected, 0.02f * expected) << "channel " << c;
  }
  // Every pixel that sees the glass refracts twice; the others keep the identity path.
  size_t glass = 0;
  for (size_t i = 0; i < r.none.samples.size(); ++i) {
    const SurfaceSample& primary = r.none.samples[i];
    const uint32_t events = r.image_space.paths[i].events & VOXR_PATH_EVENTS_MASK;
    if (primary.triangle != VOXR_NO_TRIANGLE && primary.material == kGlass) {
      ++glass;
      EXPECT_EQ(events, 2u) << "pixel " << i;
    } else {
      EXPECT_EQ(events, 0u) << "pixel " << i;
    }
  }
  EXPECT_GT(glass, size_t(kWidth) * kHeight / 10);
}

// The exact exit direction of the camera ray `v` (unit) from the eye through the ideal ball; false on a
// miss or total internal reflection.
bool exact_exit(glm::vec3 eye, glm::vec3 v, glm::vec3& t2) {
  const float b = glm::dot(eye, v), c = glm::dot(eye, eye) - kRadius * kRadius;
  if (b * b - c <= 0.0f) return false;
  const glm::vec3 p1 = eye + (-b - std::sqrt(b * b - c)) * v;
  const glm::vec3 t1 = glm::refract(v, p1 / kRadius, 1.0f / kIor);
  const glm::vec3 p2 = p1 - 2.0f * glm::dot(p1, t1) * t1;  // the chord's other end
  t2 = glm::refract(t1, -p2 / kRadius, kIor);
  return glm::dot(t2, t2) > 0.5f;
}

TEST(ImageSpaceRefraction, ExitDirectionsFollowTheBallAtModerateIncidence) {
  // A ball is where d_V and d_N blend exactly right near normal incidence: the approximate exit directions
  // stay close to the exact ones while the incidence is moderate.
  const TriangleSoup soup = scene(false);
  const Rendered r = render(soup, EnvironmentMap::checker());
  const CameraFrame cam = camera();
  size_t checked = 0;
  double worst = 0.0, sum = 0.0;
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) {
      const size_t i = size_t(y) * kWidth + x;
      const glm::vec3 v = cam.ray_direction(float(x) + 0.5f, float(y) + 0.5f);
      glm::vec3 exact;
      if (!exact_exit(cam.eye, v, exact) || r.none.samples[i].material != kGlass) continue;
      const float cos_i = -glm::dot(v, vec(r.none.samples[i].normal));
      if (cos_i < std::cos(glm::radians(40.0f))) continue;
      const float c = glm::dot(glm::normalize(vec(r.image_space.paths[i].exit_direction)), exact);
      const double angle = glm::degrees(std::acos(std::clamp(c, -1.0f, 1.0f)));
      worst = std::max(worst, angle);
      sum += angle;
      ++checked;
    }
  ASSERT_GT(checked, 200u);
  EXPECT_LT(sum / double(checked), 1.2) << "mean exit direction error (degrees)";
  EXPECT_LT(worst, 3.5) << "largest exit direction error (degrees)";
  std::printf("exit direction error: mean %.3f, max %.3f degrees over %zu pixels\n", sum / double(checked),
              worst, checked);
}

TEST(ImageSpaceRefraction, FindsAnOpaqueBoxBehindTheBall) {
  const TriangleSoup soup = scene(true);
  const Rendered r = render(soup, EnvironmentMap::checker());
  expect_all_finite(r.image_space);
  // The pixels around the centre see the ball, and through it the box.
  size_t through = 0, centre = 0;
  for (int dy = -3; dy <= 3; ++dy)
    for (int dx = -3; dx <= 3; ++dx) {
      const size_t i = size_t(int(kHeight / 2) + dy) * kWidth + size_t(int(kWidth / 2) + dx);
      ASSERT_EQ(r.none.samples[i].material, kGlass);
      ++centre;
      const SurfaceSample& end = r.image_space.samples[i];
      const RefractionPath& path = r.image_space.paths[i];
      if (end.triangle != VOXR_NO_TRIANGLE && end.material == kBox && !(path.events & VOXR_PATH_ENV)) {
        ++through;
        EXPECT_NEAR(end.position[2], -2.5f, 1e-3f) << "the box's front face";
        EXPECT_LE(glm::dot(vec(end.geometric_normal), vec(path.exit_direction)), 0.0f)
            << "the end's normal faces the exit ray";
      }
    }
  EXPECT_EQ(through, centre) << "centre pixels whose path ends on the box";
  // Every glass pixel ends on the box or in the environment; the pixels that miss the glass are unchanged.
  size_t unchanged = 0;
  for (size_t i = 0; i < r.none.samples.size(); ++i) {
    const SurfaceSample& primary = r.none.samples[i];
    if (primary.triangle != VOXR_NO_TRIANGLE && primary.material == kGlass) continue;
    ++unchanged;
    ASSERT_EQ(r.image_space.image.pixels[i], r.none.image.pixels[i]) << "pixel " << i;
    ASSERT_EQ(r.image_space.samples[i].triangle, primary.triangle) << "pixel " << i;
    ASSERT_EQ(r.image_space.paths[i].events, 0u) << "pixel " << i;
  }
  EXPECT_GT(unchanged, size_t(kWidth) * kHeight / 4);
  // The glass changes what the centre shows: the box seen through the ball, not the flat-shaded ball.
  EXPECT_NE(r.image_space.image.pixels[centre_pixel()], r.none.image.pixels[centre_pixel()]);
}

TEST(ImageSpaceRefraction, ConstantEnvironmentWithoutInwardDistancesStillFinite) {
  // d_N missing (an empty list): d falls back to d_V; the centre still passes straight through.
  const TriangleSoup soup = scene(false);
  FrameRenderer renderer(test::runtime());
  FixedInwardDistances no_d_n({});
  renderer.set_scene(soup, materials(), &no_d_n);
  renderer.set_environment(EnvironmentMap::constant(glm::vec3(0.5f, 0.6f, 0.7f)));
  const RenderOptions o = options(RefractionMethod::kImageSpace);
  renderer.prepare(o);
  const RenderedFrame f = renderer.render(light(), camera(), o);
  expect_all_finite(f);
  const RefractionPath& path = f.paths[centre_pixel()];
  EXPECT_EQ(path.events & VOXR_PATH_EVENTS_MASK, 2u);
  EXPECT_NEAR(path.exit_position[2], -kRadius, 0.02f);
}

}  // namespace
}  // namespace voxr
