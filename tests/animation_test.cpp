// Deforming scenes (core/animation.h): the "animation" keys of a scene file, the errors naming their key
// path, keyframe interpolation (exact at keys, linear and slerp midway, held outside), sway (zero at the
// base) and twist (the stated angle at height h), and posing the whole scene with a fixed anchor.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <string>

#include "core/animation.h"
#include "core/scene.h"
#include "util/error.h"

namespace voxr {
namespace {

std::string scene_error(const std::string& text) {
  try {
    parse_scene(text, "s.json", ".");
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

// A box mesh with the given "animation" JSON (and an optional scene-level "animation").
std::string box_scene(const std::string& animation, const std::string& scene_animation = "") {
  return R"({"meshes": [{"generator": "box", "params": {"lo": [-1, 0, -1], "hi": [1, 2, 1]}, "animation": )" +
         animation + "}]" + (scene_animation.empty() ? "" : ", \"animation\": " + scene_animation) + "}";
}

TEST(Animation, ParsesKeysDeformsAndFps) {
  const Scene scene = parse_scene(box_scene(R"({"keys": [{"time": 0}, {"time": 1.5, "scale": 2,
      "rotate_deg": [0, 90, 0], "translate": [1, 2, 3]}], "deform": [{"kind": "sway", "amplitude": 0.1,
      "frequency_hz": 2, "axis": [0, 0, 3], "phase_per_unit": 0.5}, {"kind": "twist", "degrees_per_unit": 30,
      "frequency_hz": 0.25}]})",
                                            R"({"fps": 30})"),
                                  "s.json", ".");
  ASSERT_EQ(scene.meshes.size(), 1u);
  const MeshAnimation& a = scene.meshes[0].animation;
  ASSERT_EQ(a.keys.size(), 2u);
  EXPECT_EQ(a.keys[1].time, 1.5);
  EXPECT_EQ(a.keys[1].scale, glm::vec3(2.0f));
  EXPECT_EQ(a.keys[1].rotate_deg, glm::vec3(0, 90, 0));
  EXPECT_EQ(a.keys[1].translate, glm::vec3(1, 2, 3));
  EXPECT_EQ(a.keys[0].scale, glm::vec3(1.0f));
  ASSERT_EQ(a.deforms.size(), 2u);
  EXPECT_EQ(a.deforms[0].kind, DeformKind::kSway);
  EXPECT_EQ(a.deforms[0].axis, glm::vec3(0, 0, 1));  // normalized
  EXPECT_EQ(a.deforms[0].amplitude, 0.1f);
  EXPECT_EQ(a.deforms[0].phase_per_unit, 0.5f);
  EXPECT_EQ(a.deforms[1].kind, DeformKind::kTwist);
  EXPECT_EQ(a.deforms[1].degrees_per_unit, 30.0f);
  EXPECT_EQ(a.deforms[1].frequency_hz, 0.25f);
  EXPECT_EQ(scene.fps, 30.0);
  EXPECT_TRUE(is_animated(scene));
  EXPECT_EQ(parse_scene(box_scene(R"({"keys": [{"time": 0}]})"), "s.json", ".").fps, kDefaultFps);
  EXPECT_FALSE(is_animated(
      parse_scene(R"({"meshes": [{"generator": "box"}], "animation": {"fps": 12}})", "s.json", ".")));
}

TEST(Animation, ErrorsNameTheKeyPath) {
  struct Case {
    std::string text, needle;
  };
  for (const Case& c : std::vector<Case>{
           {box_scene(R"({"keys": [{"time": 0}, {"time": 0}]})"),
            "s.json: 'meshes[0].animation.keys[1].time' must be greater than the previous key's"},
           {box_scene(R"({"keys": [{"time": 1}, {"time": 0.5}]})"), "'meshes[0].animation.keys[1].time'"},
           {box_scene(R"({"keys": [{"translate": [0, 0, 0]}]})"),
            "missing required key 'meshes[0].animation.keys[0].time'"},
           {box_scene(R"({"keys": [{"time": -1}]})"), "'meshes[0].animation.keys[0].time' must be"},
           {box_scene(R"({"keys": [{"time": 0, "scale": 0}]})"),
            "'meshes[0].animation.keys[0].scale' must not be 0"},
           {box_scene(R"({"keys": [{"time": 0, "rotate": [0, 0, 0]}]})"),
            "unknown key 'meshes[0].animation.keys[0].rotate' (did you mean "
            "'meshes[0].animation.keys[0].rotate_deg'?)"},
           {box_scene(R"({"keys": []})"), "'meshes[0].animation.keys' must be a non-empty array"},
           {box_scene(R"({})"), "'meshes[0].animation' needs 'keys' or 'deform'"},
           {box_scene(R"({"deform": [{"kind": "wobble"}]})"),
            "'meshes[0].animation.deform[0].kind' must be sway or twist"},
           {box_scene(R"({"deform": [{"amplitude": 1}]})"),
            "missing required key 'meshes[0].animation.deform[0].kind'"},
           {box_scene(R"({"deform": [{"kind": "sway", "frequency_hz": 1}]})"),
            "missing required key 'meshes[0].animation.deform[0].amplitude'"},
           {box_scene(R"({"deform": [{"kind": "sway", "amplitude": 1, "frequency_hz": 0}]})"),
            "'meshes[0].animation.deform[0].frequency_hz' must be positive"},
           {box_scene(
                R"({"deform": [{"kind": "sway", "amplitude": 1, "frequency_hz": 1, "axis": [0, 0, 0]}]})"),
            "'meshes[0].animation.deform[0].axis' must not be zero"},
           {box_scene(R"({"deform": [{"kind": "twist", "frequency_hz": 1, "amplitude": 1}]})"),
            "unknown key 'meshes[0].animation.deform[0].amplitude'"},
           {box_scene(
                R"({"deform": [{"kind": "twist", "degrees_per_unit": 10, "frequency_hz": 1}], "speed": 1})"),
            "unknown key 'meshes[0].animation.speed'"},
           {box_scene(R"({"keys": [{"time": 0}]})", R"({"fps": 0})"),
            "'animation.fps' must be in (0, 10000]"},
           {box_scene(R"({"keys": [{"time": 0}]})", R"({"rate": 24})"), "unknown key 'animation.rate'"},
       }) {
    const std::string error = scene_error(c.text);
    EXPECT_NE(error.find(c.needle), std::string::npos) << c.text << "\n  got: " << error;
  }
}

void expect_near(glm::vec3 a, glm::vec3 b, float tolerance) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(Animation, KeysAreExactAtKeysLinearMidwayAndHeldOutside) {
  const std::vector<TransformKey> keys{
      {1.0, glm::vec3(1.0f), glm::vec3(0, 0, 0), glm::vec3(0.3f, 1.7f, -2.1f)},
      {3.0, glm::vec3(3.0f), glm::vec3(0, 90, 0), glm::vec3(4.1f, -0.2f, 5.5f)}};
  for (double t : {0.0, 1.0}) {  // held before the first key, exact at it
    const KeyPose p = interpolate_keys(keys, t);
    EXPECT_EQ(p.translate, keys[0].translate) << t;
    EXPECT_EQ(p.scale, keys[0].scale) << t;
    EXPECT_EQ(p.rotation, glm::quat(1, 0, 0, 0)) << t;
  }
  for (double t : {3.0, 10.0}) {  // exact at the last key, held after it
    const KeyPose p = interpolate_keys(keys, t);
    EXPECT_EQ(p.translate, keys[1].translate) << t;
    EXPECT_EQ(p.scale, keys[1].scale) << t;
  }
  const KeyPose mid = interpolate_keys(keys, 2.0);
  expect_near(mid.translate, 0.5f * (keys[0].translate + keys[1].translate), 1e-6f);
  expect_near(mid.scale, glm::vec3(2.0f), 1e-6f);
  // Slerp midway: 45 degrees about Y.
  const glm::mat4 m = mid.matrix();
  const glm::mat4 expected = make_transform(glm::vec3(2.0f), glm::vec3(0, 45, 0), mid.translate);
  for (int c = 0; c < 4; ++c) expect_near(glm::vec3(m[c]), glm::vec3(expected[c]), 1e-6f);
  // At a key the matrix is the key's transform (the scene's "transform" convention).
  const glm::mat4 at_key = interpolate_keys(keys, 3.0).matrix();
  const glm::mat4 key_transform = make_transform(keys[1].scale, keys[1].rotate_deg, keys[1].translate);
  for (int c = 0; c < 4; ++c) expect_near(glm::vec3(at_key[c]), glm::vec3(key_transform[c]), 1e-5f);
}

TEST(Animation, SlerpTakesTheShorterArc) {
  const std::vector<TransformKey> keys{{0.0, glm::vec3(1.0f), glm::vec3(0, 170, 0), glm::vec3(0.0f)},
                                       {1.0, glm::vec3(1.0f), glm::vec3(0, -170, 0), glm::vec3(0.0f)}};
  // Midway through the 20-degree arc across 180 degrees, not the 340-degree one through 0.
  const glm::vec3 x = glm::vec3(interpolate_keys(keys, 0.5).matrix() * glm::vec4(1, 0, 0, 0));
  expect_near(x, glm::vec3(-1, 0, 0), 1e-5f);
}

TEST(Animation, SwayIsZeroAtTheBaseAndGrowsWithHeight) {
  Deform sway;
  sway.kind = DeformKind::kSway;
  sway.amplitude = 0.1f;
  sway.frequency_hz = 0.5f;
  sway.axis = glm::vec3(1, 0, 0);
  sway.phase_per_unit = 0.0f;
  const double base = -0.5, t = 0.5;  // sin(2 pi 0.5 0.5) = 1
  for (double x : {-1.0, 0.0, 2.0}) {
    const glm::dvec3 at_base(x, base, 0.25);
    EXPECT_EQ(deform_point({sway}, at_base, base, t), at_base);
  }
  const glm::dvec3 p = deform_point({sway}, glm::dvec3(0.0, base + 2.0, 0.0), base, t);
  EXPECT_NEAR(p.x, 0.1 * 2.0, 1e-7);
  EXPECT_EQ(p.y, base + 2.0);
  EXPECT_EQ(p.z, 0.0);
  // At rest at t = 0.
  EXPECT_EQ(deform_point({sway}, glm::dvec3(0.3, 4.0, 0.0), base, 0.0), glm::dvec3(0.3, 4.0, 0.0));
}

TEST(Animation, TwistRotatesByTheStatedAngleAtHeightH) {
  Deform twist;
  twist.kind = DeformKind::kTwist;
  twist.degrees_per_unit = 30.0f;
  twist.frequency_hz = 0.25f;
  const double t = 1.0;  // sin(2 pi 0.25 1) = 1: the peak
  for (double h : {0.0, 0.5, 1.0, 3.0}) {
    const glm::dvec3 p(1.0, 2.0 + h, 0.0);
    const glm::dvec3 q = deform_point({twist}, p, 2.0, t);
    const double angle = std::atan2(-q.z, q.x);  // counter-clockwise seen from +Y
    EXPECT_NEAR(glm::degrees(angle), 30.0 * h, 1e-9) << h;
    EXPECT_NEAR(glm::length(glm::dvec2(q.x, q.z)), 1.0, 1e-12);
    EXPECT_EQ(q.y, p.y);
  }
}

TEST(Animation, PosingUsesOneAnchorAndMovesOnlyWhatIsAnimated) {
  const Scene scene = parse_scene(
      R"({"meshes": [{"generator": "plane", "params": {"size": [4, 4]}},
                     {"generator": "box", "params": {"lo": [-0.5, 0, -0.5], "hi": [0.5, 1, 0.5]},
                      "transform": {"translate": [0, 0, 1]},
                      "animation": {"keys": [{"time": 0}, {"time": 2, "translate": [2, 0, 0]}]}}]})",
      "s.json", ".");
  const glm::dvec3 anchor = animation_anchor(scene);
  const TriangleSoup at0 = pose_scene(scene, 0.0, anchor);
  const TriangleSoup at1 = pose_scene(scene, 1.0, anchor);
  // scene_triangles is frame 0, with the same anchor.
  const TriangleSoup rest = scene_triangles(scene);
  EXPECT_EQ(rest.anchor, anchor);
  ASSERT_EQ(rest.positions.size(), at0.positions.size());
  for (size_t i = 0; i < rest.positions.size(); ++i) EXPECT_EQ(rest.positions[i], at0.positions[i]) << i;
  ASSERT_EQ(at1.triangles.size(), at0.triangles.size());
  for (size_t i = 0; i < at0.triangles.size(); ++i) EXPECT_EQ(at0.triangles[i], at1.triangles[i]);
  const size_t plane = scene.meshes[0].soup.positions.size();
  for (size_t i = 0; i < at0.positions.size(); ++i) {
    const glm::vec3 d = glm::vec3(at1.positions[i] - at0.positions[i]);
    if (i < plane)
      EXPECT_EQ(d, glm::vec3(0.0f)) << i;
    else
      expect_near(d, glm::vec3(1, 0, 0), 1e-6f);  // halfway to translate [2, 0, 0], after "transform"
  }
}

TEST(Animation, PosesBeyondTheCoordinateLimitAreErrors) {
  // Each key is a finite number; the pose at t = 1 lies beyond the readers' 1e30, and at t = 0.5 too.
  const Scene scene = parse_scene(
      box_scene(R"({"keys": [{"time": 0}, {"time": 1, "translate": [1e35, 0, 0]}]})"), "s.json", ".");
  const glm::dvec3 anchor = animation_anchor(scene);
  EXPECT_NO_THROW(pose_scene(scene, 0.0, anchor));
  for (double t : {0.5, 1.0}) {
    try {
      pose_scene(scene, t, anchor);
      FAIL() << "no error at t = " << t;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("s.json: the animation at t = "), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("beyond the mesh readers' limit of 1e+30"), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace voxr
