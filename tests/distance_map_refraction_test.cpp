// Layered distance-map refraction (render/distance_map_refraction.h, GPU Gems 3 ch. 17): the rasterizer's
// depth peeling against the sorted CPU reference words; a glass ball's centre pixel passes straight through
// with two refractions; an opaque box behind the ball is found in the environment layer; a tilted slab
// shifts the centre ray by the textbook offset; a thick glass shell needs its second layer (one layer loses
// the paths inside the wall: the method's characteristic failure); every refraction scene renders finite
// with shadows.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "core/generators.h"
#include "core/scene.h"
#include "refraction_ball.h"
#include "render/distance_map_refraction.h"
#include "render/environment_map.h"
#include "render/frame_renderer.h"
#include "render/reference_raster.h"
#include "render/render_scene.h"
#include "test_support.h"

namespace voxr {
namespace {

using namespace test::ball;

constexpr uint64_t kEmpty = ~uint64_t(0);

RenderOptions options(uint32_t layers = 4, uint32_t layer_res = 128) {
  RenderOptions o;
  o.shadows = ShadowMethod::kNone;
  o.keep_samples = true;
  o.refraction.method = RefractionMethod::kDistanceMaps;
  o.refraction.layers = layers;
  o.refraction.layer_res = layer_res;
  return o;
}

RenderedFrame render(const TriangleSoup& soup, const RenderOptions& o, const CameraFrame& cam = camera()) {
  FrameRenderer renderer(test::runtime());
  renderer.set_scene(soup, materials());
  renderer.set_environment(EnvironmentMap::checker());
  renderer.prepare(o);
  return renderer.render(light(), cam, o);
}

float angle_deg(const glm::vec3& a, const glm::vec3& b) {
  return glm::degrees(std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0f, 1.0f)));
}

TEST(DistanceMapRefraction, CubeFacesAreRightHandedAndSeeTheirOwnDirections) {
  // Every face's basis is orthonormal with right = forward x up (CameraFrame's), and each texel centre's
  // ray has its largest component along the face's forward axis (the kernel's face choice).
  for (uint32_t face = 0; face < 6; ++face) {
    const CameraFrame f = cube_face_frame(glm::vec3(0.5f, -1.0f, 2.0f), face, 8, 0.01f, 10.0f);
    EXPECT_EQ(f.right, glm::cross(f.forward, f.up)) << "face " << face;
    EXPECT_EQ(glm::dot(f.forward, f.up), 0.0f);
    for (uint32_t y = 0; y < 8; ++y)
      for (uint32_t x = 0; x < 8; ++x) {
        const glm::vec3 d = f.ray_direction(float(x) + 0.5f, float(y) + 0.5f);
        const int axis = face / 2;
        EXPECT_GT(std::abs(d[axis]), std::abs(d[(axis + 1) % 3])) << "face " << face;
        EXPECT_GT(std::abs(d[axis]), std::abs(d[(axis + 2) % 3])) << "face " << face;
        EXPECT_GT(d[axis] * f.forward[axis], 0.0f) << "face " << face;
      }
  }
}

TEST(DistanceMapRefraction, ReferencePointIsTheDielectricsCentre) {
  // The ball (radius 1 at the origin) and an opaque slab behind it: the reference point is the ball's
  // bounds' centre, its sphere holds the ball's bounds, the scene's sphere the slab's far corners.
  const DistanceMapOrigin o = distance_map_origin(scene(true), materials());
  EXPECT_NEAR(glm::length(o.reference), 0.0f, 1e-5f);
  EXPECT_NEAR(o.radius, 1.01f * std::sqrt(3.0f), 1e-4f);
  EXPECT_NEAR(o.scene_radius, 1.01f * std::sqrt(4.0f + 4.0f + 9.0f), 1e-4f);
}

// Issue 20, kind 6: the camera-inside check. A glass box (material 1) with a glass box of another glass
// (material 2) inside it and an opaque box (material 0) beside them: a point is inside the dielectric of the
// lowest material id that holds it, in none outside or in the opaque box.
TEST(DistanceMapRefraction, DielectricAroundAPointByWinding) {
  std::vector<Material> mats(3);
  mats[0].name = "stone";
  mats[1].name = "glass";
  mats[1].kind = MaterialKind::kDielectric;
  mats[2].name = "flint";
  mats[2].kind = MaterialKind::kDielectric;
  TriangleSoup soup;
  soup.append(make_box({-2, -2, -2}, {2, 2, 2}), glm::mat4(1.0f), 1);
  soup.append(make_box({-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}), glm::mat4(1.0f), 2);
  soup.append(make_box({3, -1, -1}, {5, 1, 1}), glm::mat4(1.0f), 0);
  EXPECT_EQ(dielectric_around(soup, mats, {1.5f, 0.0f, 0.0f}), std::optional<uint32_t>(1u));
  EXPECT_EQ(dielectric_around(soup, mats, {-1.0f, 1.0f, 0.25f}), std::optional<uint32_t>(1u));
  // Inside the inner box: inside both; the lowest odd material id is reported (glass, then flint).
  EXPECT_EQ(dielectric_around(soup, mats, {0.1f, 0.2f, 0.0f}), std::optional<uint32_t>(1u));
  EXPECT_EQ(dielectric_around(soup, mats, {0.0f, 0.0f, 3.0f}), std::nullopt);
  EXPECT_EQ(dielectric_around(soup, mats, {4.0f, 0.0f, 0.0f}), std::nullopt) << "inside the opaque box";
  EXPECT_EQ(dielectric_around(soup, mats, {-9.0f, -9.0f, -9.0f}), std::nullopt);
  // A box of the same glass nested in the first (by parity, an air bubble): inside both, so inside glass.
  soup.append(make_box({1.0f, 1.0f, 1.0f}, {1.8f, 1.8f, 1.8f}), glm::mat4(1.0f), 1);
  EXPECT_EQ(dielectric_around(soup, mats, {1.4f, 1.4f, 1.4f}), std::optional<uint32_t>(1u));
  // Wound inside out, the same box is a cavity in the glass: outside every dielectric.
  TriangleSoup cavity;
  cavity.append(make_box({-2, -2, -2}, {2, 2, 2}), glm::mat4(1.0f), 1);
  const size_t first = cavity.triangles.size();
  cavity.append(make_box({1.0f, 1.0f, 1.0f}, {1.8f, 1.8f, 1.8f}), glm::mat4(1.0f), 1);
  for (size_t t = first; t < cavity.triangles.size(); ++t)
    std::swap(cavity.triangles[t].y, cavity.triangles[t].z);
  EXPECT_EQ(dielectric_around(cavity, mats, {1.4f, 1.4f, 1.4f}), std::nullopt);
  EXPECT_EQ(dielectric_around(cavity, mats, {0.0f, 0.0f, 0.0f}), std::optional<uint32_t>(1u));
}

// Rendering from inside the glass is refused with the material's name (it rendered a dark picture, every
// path lost); from outside the same scene renders.
TEST(DistanceMapRefraction, CameraInsideGlassIsRefused) {
  const TriangleSoup ball = scene(false);
  const std::vector<Material> mats = materials();
  FrameRenderer renderer(test::runtime());
  renderer.set_scene(ball, mats);  // kept by reference
  renderer.set_environment(EnvironmentMap::checker());
  const RenderOptions o = options(2, 32);
  renderer.prepare(o);
  CameraFrame inside = camera();
  inside.eye = glm::vec3(0.1f, 0.2f, 0.3f);  // within the unit ball
  try {
    renderer.render(light(), inside, o);
    ADD_FAILURE() << "a camera inside the ball was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'camera.position' (0.1, 0.2, 0.3) (anchor-relative) is inside the "
                                         "dielectric '" +
                                         mats[kGlass].name + "'"),
              std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(renderer.render(light(), camera(), o));
}

TEST(DistanceMapRefraction, PeelingMatchesTheSortedReferenceLayers) {
  // Three parallel quads seen from above: y = 1 (side 1), y = 0 (side 2), y = -1 (side 3), each its own
  // material (kind) so that the reference can raster each alone with the same triangle ids.
  TriangleSoup soup;
  soup.append(make_plane(glm::vec2(1.0f)), glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0)), 0);
  soup.append(make_plane(glm::vec2(2.0f)), glm::mat4(1.0f), 1);
  soup.append(make_plane(glm::vec2(3.0f)), glm::translate(glm::mat4(1.0f), glm::vec3(0, -1, 0)), 2);
  std::vector<RenderMaterial> mats(3);
  for (uint32_t k = 0; k < 3; ++k) mats[k] = RenderMaterial{}, mats[k].kind = k;
  CameraFrame frame;
  frame.eye = glm::vec3(0.1f, 4.0f, 0.05f);
  frame.forward = glm::vec3(0, -1, 0);
  frame.right = glm::vec3(1, 0, 0);
  frame.up = glm::vec3(0, 0, -1);
  frame.tan_half_fov_y = 0.5f;
  frame.width = 61;
  frame.height = 47;
  frame.near_plane = 0.1f;
  frame.far_plane = 10.0f;
  const RasterTarget target = camera_target(frame);
  const size_t pixels = size_t(frame.width) * frame.height;
  // Expected: per pixel, the quads' own words in depth order.
  std::vector<std::vector<uint64_t>> sorted(pixels);
  for (uint32_t k = 0; k < 3; ++k) {
    RasterTarget alone = target;
    alone.kind_mask = 1u << k;
    const ReferenceRaster ref = reference_raster(soup, alone, mats);
    for (size_t i = 0; i < pixels; ++i)
      if (ref.visibility[i] != kEmpty) sorted[i].push_back(ref.visibility[i]);
  }
  for (auto& s : sorted) std::sort(s.begin(), s.end());

  ClRuntime& cl = test::runtime();
  const DeviceMesh mesh(cl, soup);
  cl::Buffer mat_buffer = cl.buffer(mats.size() * sizeof(RenderMaterial), "test materials");
  cl.upload(mat_buffer, mats.data(), mats.size() * sizeof(RenderMaterial), "upload materials");
  VisibilityRasterizer raster(cl);
  RasterBins bins;
  raster.bin(mesh, target, mat_buffer, 3, bins);
  GrowingBuffer layer[2];
  size_t counts[4] = {0, 0, 0, 0};
  for (uint32_t l = 0; l < 4; ++l) {
    if (l == 0)
      raster.rasterize_depth(bins, layer[0]);
    else
      raster.rasterize_depth_peel(bins, layer[(l + 1) % 2].buffer, kDistanceMapPeelUlps, layer[l % 2]);
    std::vector<uint64_t> words(pixels);
    cl.download(layer[l % 2].buffer, words.data(), pixels * 8, "readback layer");
    for (size_t i = 0; i < pixels; ++i) {
      const uint64_t expected = l < sorted[i].size() ? sorted[i][l] : kEmpty;
      ASSERT_EQ(words[i], expected) << "layer " << l << " pixel (" << i % frame.width << ", "
                                    << i / frame.width << ")";
      counts[l] += words[i] != kEmpty;
    }
  }
  // Each layer is the next quad where it covers: some of each, none beyond the third.
  EXPECT_GT(counts[0], counts[1]);
  EXPECT_GT(counts[1], counts[2]);
  EXPECT_GT(counts[2], 0u);
  EXPECT_EQ(counts[3], 0u);
}

TEST(DistanceMapRefraction, BallCentrePassesStraightThroughWithTwoRefractions) {
  const TriangleSoup soup = scene(false);
  const RenderedFrame f = render(soup, options());
  expect_all_finite(f);
  const RefractionPath& path = f.paths[centre_pixel()];
  EXPECT_EQ(path.events & VOXR_PATH_EVENTS_MASK, 2u);
  EXPECT_EQ(path.events & (VOXR_PATH_TIR | VOXR_PATH_LOST), 0u);
  EXPECT_TRUE(path.events & VOXR_PATH_ENV);
  EXPECT_EQ(f.samples[centre_pixel()].triangle, VOXR_NO_TRIANGLE);
  EXPECT_LT(angle_deg(vec(path.exit_direction), camera().forward), 0.5f);
  // The analytic exit is (0, 0, -1); the tessellated sphere lies within 1e-3 of it there.
  EXPECT_NEAR(path.exit_position[0], 0.0f, 0.01f);
  EXPECT_NEAR(path.exit_position[1], 0.0f, 0.01f);
  EXPECT_NEAR(path.exit_position[2], -kRadius, 0.01f);
  const float r0 = (kIor - 1.0f) / (kIor + 1.0f);
  const float fr = r0 * r0;
  for (int c = 0; c < 3; ++c) {
    const float expected = (1.0f - fr) * (1.0f - fr) * std::exp(-kAbsorption[c] * 2.0f * kRadius);
    EXPECT_NEAR(path.throughput[c], expected, 0.01f * expected) << "channel " << c;
  }
  // A convex refractor about the reference point: every glass pixel meets two or more interfaces (total
  // internal reflection near the rim); a few grazing paths at the rim, whose next surface lies within a
  // texel's footprint, are lost (rejected as the surface just left).
  size_t glass = 0, lost = 0;
  for (const RefractionPath& p : f.paths) {
    if ((p.events & VOXR_PATH_EVENTS_MASK) == 0) continue;
    ++glass;
    lost += (p.events & VOXR_PATH_LOST) != 0;
    EXPECT_GE(p.events & VOXR_PATH_EVENTS_MASK, 2u);
  }
  EXPECT_GT(glass, size_t(kWidth) * kHeight / 10);
  EXPECT_LT(lost, glass / 50) << "lost paths";
  std::printf("%zu of %zu glass pixels lost\n", lost, glass);
}

TEST(DistanceMapRefraction, FindsAnOpaqueBoxBehindTheBallInTheEnvironmentLayer) {
  const TriangleSoup soup = scene(true);
  const RenderedFrame f = render(soup, options());
  expect_all_finite(f);
  for (int dy = -3; dy <= 3; ++dy)
    for (int dx = -3; dx <= 3; ++dx) {
      const size_t i = size_t(int(kHeight / 2) + dy) * kWidth + size_t(int(kWidth / 2) + dx);
      const SurfaceSample& end = f.samples[i];
      const RefractionPath& path = f.paths[i];
      ASSERT_EQ(path.events & VOXR_PATH_EVENTS_MASK, 2u) << "pixel " << i;
      ASSERT_EQ(end.material, kBox) << "pixel " << i;
      EXPECT_EQ(path.events & VOXR_PATH_ENV, 0u);
      EXPECT_NEAR(end.position[2], -2.5f, 1e-3f) << "the box's front face";
      EXPECT_LE(glm::dot(vec(end.geometric_normal), vec(path.exit_direction)), 0.0f);
    }
}

TEST(DistanceMapRefraction, TiltedSlabShiftsTheRayByTheTextbookOffset) {
  // A glass slab 0.5 thick turned 40 degrees about y: the centre ray leaves parallel to itself, shifted by
  // t sin(theta - theta_t) / cos(theta_t). The exit is found by the search in nearest texels: within 0.01
  // (the distance stored at a 128^2 texel varies by about that much across it here).
  const float t = 0.5f, theta = glm::radians(40.0f);
  TriangleSoup soup;
  const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), theta, glm::vec3(0.0f, 1.0f, 0.0f));
  soup.append(make_box(glm::vec3(-1.0f, -1.0f, -t / 2), glm::vec3(1.0f, 1.0f, t / 2)), turn, kGlass);
  const RenderedFrame f = render(soup, options());
  const RefractionPath& path = f.paths[centre_pixel()];
  ASSERT_EQ(path.events & VOXR_PATH_EVENTS_MASK, 2u);
  EXPECT_LT(angle_deg(vec(path.exit_direction), camera().forward), 0.5f);
  const float theta_t = std::asin(std::sin(theta) / kIor);
  const float expected = t * std::sin(theta - theta_t) / std::cos(theta_t);
  const glm::vec3 v = camera().forward;
  const glm::vec3 q = vec(path.exit_position) - camera().eye;
  const float offset = glm::length(q - glm::dot(q, v) * v);
  EXPECT_NEAR(offset, expected, 0.01f) << "textbook " << expected;
  std::printf("slab offset %.5f, textbook %.5f\n", offset, expected);
}

TEST(DistanceMapRefraction, OneLayerLosesTheShellsOuterWallWhereFourFindIt) {
  // A thick glass shell: radius 1 with a cavity of radius 0.5 (the same glass, wound inward: media enter and
  // leave by winding). From the centre the cavity is the first layer and the outer sphere the second. The
  // centre ray meets four interfaces; with one layer the outer wall is never found from inside the glass:
  // the path is lost after three (a characteristic failure, reported as VOXR_PATH_LOST, not hidden).
  TriangleSoup soup, cavity = make_uv_sphere(0.5f, 32, 64);
  for (glm::uvec4& t : cavity.triangles) std::swap(t.y, t.z);
  soup.append(make_uv_sphere(1.0f, 48, 96), glm::mat4(1.0f), kGlass);
  soup.append(cavity, glm::mat4(1.0f), kGlass);
  const RenderedFrame four = render(soup, options(4));
  const RenderedFrame one = render(soup, options(1));
  expect_all_finite(four);
  expect_all_finite(one);
  const RefractionPath& p4 = four.paths[centre_pixel()];
  const RefractionPath& p1 = one.paths[centre_pixel()];
  EXPECT_EQ(p4.events & VOXR_PATH_EVENTS_MASK, 4u);
  EXPECT_TRUE(p4.events & VOXR_PATH_ENV);
  EXPECT_EQ(p4.events & VOXR_PATH_LOST, 0u);
  EXPECT_NEAR(p4.exit_position[2], -1.0f, 0.01f);
  EXPECT_EQ(p1.events & VOXR_PATH_EVENTS_MASK, 3u);
  EXPECT_TRUE(p1.events & VOXR_PATH_LOST);
  size_t lost1 = 0, lost4 = 0, differ = 0, glass = 0;
  for (size_t i = 0; i < four.paths.size(); ++i) {
    if ((four.paths[i].events & VOXR_PATH_EVENTS_MASK) == 0) continue;
    ++glass;
    lost1 += (one.paths[i].events & VOXR_PATH_LOST) != 0;
    lost4 += (four.paths[i].events & VOXR_PATH_LOST) != 0;
    differ += (one.paths[i].events & VOXR_PATH_EVENTS_MASK) != (four.paths[i].events & VOXR_PATH_EVENTS_MASK);
  }
  // Every path that enters the glass must leave through the outer wall: one layer loses them all.
  EXPECT_EQ(lost1, glass);
  EXPECT_LT(lost4, glass / 20);
  EXPECT_GT(differ, glass / 2);
}

TEST(DistanceMapRefraction, EveryRefractionSceneRendersFiniteWithShadows) {
  for (const char* name : {"glass-sphere.json", "bunny-glass-130.json", "glass-vase.json", "ball-figure.json",
                           "gem.json", "thin-shell.json", "sphere-nearby.json", "default.json"}) {
    SCOPED_TRACE(name);
    Scene scene = load_scene(std::string(VOXR_SOURCE_DIR) + "/data/scenes/" + name);
    const std::vector<Material> mats = scene.materials;
    const EnvironmentMap environment = make_environment_map(scene.environment);
    const TriangleSoup soup = take_scene_triangles(scene);
    FrameRenderer renderer(test::runtime());
    renderer.set_scene(soup, mats);
    renderer.set_environment(environment);
    RenderOptions o = options(4, 64);
    o.shadows = ShadowMethod::kVoxel;
    o.shadow_resolution = 64;
    renderer.prepare(o);
    const CameraFrame cam = make_camera_frame(scene.camera, soup.anchor, soup.bounds(), 80, 60);
    const RenderedFrame f =
        renderer.render(render_light(scene.light, environment.mean(), soup.anchor), cam, o);
    expect_all_finite(f);
    for (const glm::vec4& p : f.image.pixels) ASSERT_GE(std::min({p.x, p.y, p.z}), 0.0f);
    size_t glass = 0;
    for (const RefractionPath& p : f.paths) glass += (p.events & VOXR_PATH_EVENTS_MASK) > 0;
    EXPECT_GT(glass, 50u);
  }
}

}  // namespace
}  // namespace voxr
