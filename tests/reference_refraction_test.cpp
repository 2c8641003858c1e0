// The refraction reference (reference_refraction.h) against optics worked by hand: the centre ray through a
// glass sphere, the lateral offset of a tilted slab, total internal reflection in a right-angle prism, the
// full model against the matched one; coincident surfaces (glass standing on a floor) and a thin slab; the
// refraction metrics on hand-made paths; Wyman's d_N by ray casting.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/generators.h"
#include "metrics/refraction_metrics.h"
#include "reference/inward_distance.h"
#include "reference/reference_refraction.h"
#include "reference/reference_scene.h"
#include "render/environment_map.h"
#include "render/render_scene.h"
#include "render/vertex_normals.h"
#include "test_support.h"
#include "util/error.h"

namespace voxr {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

glm::vec3 vec(const float* v) {
  return glm::vec3(v[0], v[1], v[2]);
}

double angle_deg(const glm::vec3& a, const glm::vec3& b) {
  const glm::dvec3 u(a), v(b);
  return std::atan2(glm::length(glm::cross(u, v)), glm::dot(u, v)) / kDegree;
}

Material glass(float ior, glm::vec3 sigma) {
  Material m;
  m.name = "glass";
  m.kind = MaterialKind::kDielectric;
  m.ior = ior;
  m.absorption = sigma;
  return m;
}

Material opaque(glm::vec3 color = glm::vec3(0.8f)) {
  Material m;
  m.name = "opaque";
  m.color = color;
  return m;
}

RenderLight light_from_above() {
  RenderLight l{};
  l.directional = 1;
  const glm::vec3 d = glm::normalize(glm::vec3(0.3f, -1.0f, -0.2f));
  for (int c = 0; c < 3; ++c) {
    l.direction[c] = d[c];
    l.intensity[c] = 1.0f;
    l.ambient[c] = 0.2f;
  }
  return l;
}

// A pinhole at `eye` looking along `forward`; odd sizes put the centre pixel's ray exactly along forward.
CameraFrame camera_at(glm::vec3 eye, glm::vec3 forward, float tan_half_fov, uint32_t size = 33) {
  CameraFrame c;
  c.eye = eye;
  c.forward = glm::normalize(forward);
  const glm::vec3 helper = std::abs(c.forward.y) > 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  c.right = glm::normalize(glm::cross(c.forward, helper));
  c.up = glm::cross(c.right, c.forward);
  c.tan_half_fov_y = tan_half_fov;
  c.width = c.height = size;
  return c;
}

size_t centre(const CameraFrame& c) {
  return size_t(c.height / 2) * c.width + c.width / 2;
}

void expect_finite_nonnegative(const ImageRgba& image, const char* what) {
  size_t bad = 0;
  for (const glm::vec4& p : image.pixels)
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(p[c]) || p[c] < 0.0f) ++bad;
  EXPECT_EQ(bad, 0u) << what;
}

const glm::vec3 kSphereSigma(0.2f, 0.1f, 0.05f);
const glm::vec3 kEnvironment(0.5f, 0.6f, 0.7f);

struct SphereScene {
  TriangleSoup soup = make_uv_sphere(1.0f, 64, 128);
  std::vector<Material> materials{glass(1.5f, kSphereSigma)};
  ReferenceScene scene{soup, materials};
};

// The centre ray through a glass sphere (r = 1, n = 1.5) meets both surfaces at normal incidence: it leaves
// undeviated into the environment after 2 refractions, carrying (1 - F)^2 exp(-2 sigma r) with
// F = ((n - 1) / (n + 1))^2 (Schlick is exact there). The ray passes through tessellation vertices (the
// equator's ring at x = 0), where the mesh touches the sphere, so the chord is 2r to within float rounding:
// 1 % is a loose bound, tight enough to see a missing (1 - F) (4 %) or absorption over the wrong length.
TEST(ReferenceRefraction, SphereCentreRayMatchesAnalytic) {
  const SphereScene s;
  const CameraFrame camera = camera_at({0, 0, 5}, {0, 0, -1}, 0.3f);
  const EnvironmentMap env = EnvironmentMap::constant(kEnvironment);
  const RefractionReference r = render_refraction_reference(
      s.scene, render_materials(s.materials), light_from_above(), env, camera, ReferenceModel::kMatched);
  const size_t i = centre(camera);
  const RefractionPath& p = r.paths[i];
  EXPECT_EQ(p.events, 2u | VOXR_PATH_ENV);
  EXPECT_EQ(r.ends[i].triangle, VOXR_NO_TRIANGLE);
  EXPECT_LT(angle_deg(vec(p.exit_direction), camera.forward), 0.5);
  const float f = 0.04f;  // ((1.5 - 1) / (1.5 + 1))^2
  EXPECT_NEAR(p.fresnel, f, 1e-4f);
  EXPECT_LT(angle_deg(vec(p.reflect_direction), -camera.forward), 0.5);
  for (int c = 0; c < 3; ++c) {
    const float expected = (1.0f - f) * (1.0f - f) * std::exp(-2.0f * kSphereSigma[c]);
    EXPECT_NEAR(p.throughput[c], expected, 0.01f * expected) << "channel " << c;
    // The pixel: F x the mirrored environment + throughput x the environment behind.
    EXPECT_NEAR(r.image.pixels[i][c], (f + expected) * kEnvironment[c], 0.01f * kEnvironment[c]);
  }
  // The exit point is the back of the sphere, on the axis.
  EXPECT_NEAR(glm::length(vec(p.exit_position) - glm::vec3(0, 0, -1)), 0.0f, 1e-3f);
  // A pixel that misses the sphere: the identity path, the environment.
  EXPECT_EQ(r.paths[0].events, 0u);
  EXPECT_EQ(r.paths[0].fresnel, 0.0f);
  EXPECT_EQ(r.paths[0].throughput[0], 1.0f);
  EXPECT_EQ(r.ends[0].triangle, VOXR_NO_TRIANGLE);
  EXPECT_EQ(r.image.pixels[0], glm::vec4(kEnvironment, 1.0f));
  expect_finite_nonnegative(r.image, "matched sphere");
  EXPECT_EQ(r.transmittance.size(), r.paths.size());
}

// Appends the convex polygon `points` as a fan with vertices of its own (flat normals), wound so that its
// normal points along `outward`.
void add_face(TriangleSoup& soup, std::vector<glm::vec3> points, glm::vec3 outward, uint32_t material) {
  if (glm::dot(glm::cross(points[1] - points[0], points[2] - points[0]), outward) < 0.0f)
    std::reverse(points.begin(), points.end());
  const uint32_t first = uint32_t(soup.positions.size());
  for (const glm::vec3& q : points) soup.positions.push_back(glm::vec4(q, 1.0f));
  for (uint32_t k = 1; k + 1 < points.size(); ++k)
    soup.triangles.push_back({first, first + k, first + k + 1, material});
}

// A box [lo, hi] turned by `rotation`, each face with vertices of its own: flat shading normals. (make_box
// shares its 8 corners, and inside a face the interpolated corner normals come within 45 degrees of the
// face's, e.g. 25 degrees off at a triangle's centroid, so the crease rule keeps them: its faces are not
// flat for refraction.)
void add_flat_box(TriangleSoup& soup, glm::vec3 lo, glm::vec3 hi, const glm::mat3& rotation,
                  uint32_t material) {
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      std::vector<glm::vec3> points;
      for (glm::vec2 corner : {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)}) {
        glm::vec3 q;
        q[axis] = side ? hi[axis] : lo[axis];
        q[u] = corner.x > 0 ? hi[u] : lo[u];
        q[v] = corner.y > 0 ? hi[v] : lo[v];
        points.push_back(rotation * q);
      }
      glm::vec3 outward(0.0f);
      outward[axis] = side ? 1.0f : -1.0f;
      add_face(soup, points, rotation * outward, material);
    }
}

// A glass slab of thickness t (a box 6 x 6 x t, turned about y by theta) seen by a ray at incidence theta:
// the ray leaves parallel to itself, shifted sideways by t sin(theta - theta_t) / cos(theta_t).
TEST(ReferenceRefraction, TiltedSlabShiftsTheRay) {
  const float t = 0.5f, n = 1.5f;
  const double theta = 40.0 * kDegree;
  TriangleSoup soup;
  add_flat_box(soup, {-3, -3, -t / 2}, {3, 3, t / 2},
               glm::mat3(glm::rotate(glm::mat4(1.0f), float(theta), glm::vec3(0, 1, 0))), 0);
  const std::vector<Material> materials{glass(n, glm::vec3(0.0f))};
  const ReferenceScene scene(soup, materials);
  const CameraFrame camera = camera_at({0.1f, 0.2f, 5}, {0, 0, -1}, 0.2f);
  const RefractionReference r =
      render_refraction_reference(scene, render_materials(materials), light_from_above(),
                                  EnvironmentMap::checker(64), camera, ReferenceModel::kMatched);
  const RefractionPath& p = r.paths[centre(camera)];
  EXPECT_EQ(p.events, 2u | VOXR_PATH_ENV);
  EXPECT_LT(angle_deg(vec(p.exit_direction), camera.forward), 0.1);
  const double theta_t = std::asin(std::sin(theta) / n);
  const double expected = t * std::sin(theta - theta_t) / std::cos(theta_t);
  const glm::dvec3 d(camera.forward);
  const double offset = glm::length(glm::cross(glm::dvec3(vec(p.exit_position)) - glm::dvec3(camera.eye), d));
  EXPECT_NEAR(offset, expected, 0.01 * expected);
  // Every pixel crosses the slab: two refractions, no reflection inside.
  for (const RefractionPath& q : r.paths) EXPECT_EQ(q.events, 2u | VOXR_PATH_ENV);
  expect_finite_nonnegative(r.image, "slab");
}

// A right-angle prism along y: cross-section A (0, 0), B (1, 0), C (0, 1) in (x, z), y in [-1, 1].
void add_prism(TriangleSoup& soup, uint32_t material) {
  const glm::vec3 a0(0, -1, 0), b0(1, -1, 0), c0(0, -1, 1), a1(0, 1, 0), b1(1, 1, 0), c1(0, 1, 1);
  add_face(soup, {a0, b0, b1, a1}, {0, 0, -1}, material);  // leg AB, z = 0
  add_face(soup, {a0, c0, c1, a1}, {-1, 0, 0}, material);  // leg AC, x = 0
  add_face(soup, {b0, c0, c1, b1}, {1, 0, 1}, material);   // hypotenuse BC
  add_face(soup, {a0, b0, c0}, {0, -1, 0}, material);
  add_face(soup, {a1, b1, c1}, {0, 1, 0}, material);
}

// A Porro reflection: a ray entering the prism's leg AB at normal incidence meets the hypotenuse at 45
// degrees, beyond diamond's critical angle (asin(1 / 2.42) = 24.4 degrees), is totally reflected and leaves
// through leg AC at normal incidence, turned by 90 degrees: 3 interfaces, one of them a TIR, throughput
// (1 - F)^2 exp(-sigma * 1) (0.7 + 0.3 inside).
TEST(ReferenceRefraction, PrismTotalInternalReflection) {
  const float n = 2.42f;
  const glm::vec3 sigma(0.1f, 0.2f, 0.3f);
  TriangleSoup soup;
  add_prism(soup, 0);
  soup.append(make_box({-3, -2.5f, -3}, {3, -2, 3}), glm::mat4(1.0f), 1);  // a floor to shade
  const std::vector<Material> materials{glass(n, sigma), opaque()};
  const ReferenceScene scene(soup, materials);
  const RenderLight light = light_from_above();
  const EnvironmentMap env = EnvironmentMap::checker(64);

  const CameraFrame narrow = camera_at({0.3f, 0, -3}, {0, 0, 1}, 0.04f);
  const RefractionReference r = render_refraction_reference(scene, render_materials(materials), light, env,
                                                            narrow, ReferenceModel::kMatched);
  const RefractionPath& p = r.paths[centre(narrow)];
  EXPECT_EQ(p.events, 3u | VOXR_PATH_TIR | VOXR_PATH_ENV);
  EXPECT_LT(angle_deg(vec(p.exit_direction), glm::vec3(-1, 0, 0)), 0.1);
  EXPECT_NEAR(glm::length(vec(p.exit_position) - glm::vec3(0, 0, 0.7f)), 0.0f, 1e-3f);
  const float f = ((n - 1) / (n + 1)) * ((n - 1) / (n + 1));
  for (int c = 0; c < 3; ++c) {
    const float expected = (1 - f) * (1 - f) * std::exp(-sigma[c] * 1.0f);
    EXPECT_NEAR(p.throughput[c], expected, 0.01f * expected) << "channel " << c;
  }
  for (const RefractionPath& q : r.paths) EXPECT_TRUE(q.events & VOXR_PATH_TIR);

  // Wide: rays into every face at every angle, onto the floor through the glass, TIR everywhere.
  const CameraFrame wide = camera_at({2.5f, 1.5f, -2.5f}, {-2.2f, -1.5f, 2.8f}, 0.7f, 48);
  for (ReferenceModel model : {ReferenceModel::kMatched, ReferenceModel::kFull}) {
    const RefractionReference w =
        render_refraction_reference(scene, render_materials(materials), light, env, wide, model);
    expect_finite_nonnegative(w.image, model == ReferenceModel::kFull ? "full prism" : "matched prism");
    size_t tir = 0;
    for (const RefractionPath& q : w.paths) {
      tir += (q.events & VOXR_PATH_TIR) ? 1 : 0;
      for (int c = 0; c < 3; ++c) {
        EXPECT_TRUE(std::isfinite(q.throughput[c]));
        EXPECT_TRUE(std::isfinite(q.exit_direction[c]));
      }
    }
    EXPECT_GT(tir, 0u);
  }
}

// The full model adds what the matched one leaves out (reflections inside and out, exact Fresnel): at the
// centre of a glass sphere in a constant environment both agree on the first reflection (normal incidence:
// Schlick is exact) and the transmitted light; the full one adds the light reflected once inside the back
// and sent out through the front, about 3.5 % in the least absorbing channel.
TEST(ReferenceRefraction, FullModelAddsOnlyReflections) {
  const SphereScene s;
  const CameraFrame camera = camera_at({0, 0, 5}, {0, 0, -1}, 0.3f);
  const EnvironmentMap env = EnvironmentMap::constant(kEnvironment);
  const std::vector<RenderMaterial> mats = render_materials(s.materials);
  const RefractionReference matched =
      render_refraction_reference(s.scene, mats, light_from_above(), env, camera, ReferenceModel::kMatched);
  const RefractionReference full =
      render_refraction_reference(s.scene, mats, light_from_above(), env, camera, ReferenceModel::kFull);
  expect_finite_nonnegative(full.image, "full sphere");
  const size_t i = centre(camera);
  for (int c = 0; c < 3; ++c) {
    const float m = matched.image.pixels[i][c], f = full.image.pixels[i][c];
    EXPECT_GE(f, m * 0.999f) << "channel " << c;
    EXPECT_LE(f, m * 1.05f) << "channel " << c;
  }
  // The full model's paths are the matched model's.
  EXPECT_EQ(full.paths[i].events, matched.paths[i].events);
  EXPECT_EQ(full.paths[i].throughput[0], matched.paths[i].throughput[0]);
  // A pixel that misses: the environment in both.
  EXPECT_EQ(full.image.pixels[0], matched.image.pixels[0]);
}

// Coincident surfaces (issue 19 item 4): the glass box of `hi` on an 8 x 8 floor, its bottom face exactly
// in the floor's plane. Triangles 0-11 the box (make_box: shared corners), 12-13 the floor.
struct GlassOnFloor {
  TriangleSoup soup;
  std::vector<Material> materials{glass(1.5f, glm::vec3(0.2f, 0.1f, 0.05f)), opaque()};
  GlassOnFloor() {
    soup.append(make_box({-0.5f, 0.0f, -0.5f}, {0.5f, 0.8f, 0.5f}), glm::mat4(1.0f), 0);
    soup.append(make_plane(glm::vec2(8.0f), 1), glm::mat4(1.0f), 1);
  }
};

// Of coincident hits an opaque one wins, whichever triangle comes first in the soup; of two dielectrics
// one the ray enters, then the lowest triangle id. A ray leaving a face skips it and its neighbours at the
// origin, nothing else.
TEST(ReferenceScene, CoincidentOpaqueWinsAndLeavingSkipsOnlyTheTriangleLeft) {
  for (int opaque_first = 0; opaque_first < 2; ++opaque_first) {
    TriangleSoup soup;
    test::add_square(soup, 0.0f, -1.0f, 1.0f, opaque_first ? 1 : 0);
    test::add_square(soup, 0.0f, -1.0f, 1.0f, opaque_first ? 0 : 1);
    const std::vector<Material> materials{glass(1.5f, glm::vec3(0.0f)), opaque()};
    const ReferenceScene scene(soup, materials);
    for (const glm::vec3 d : {glm::vec3(0.1f, -1.0f, 0.05f), glm::vec3(-0.2f, 1.0f, 0.3f)}) {
      const SurfaceSample s = scene.intersect(glm::vec3(0.13f, 0.0f, -0.21f) - d, d);
      ASSERT_NE(s.triangle, VOXR_NO_TRIANGLE);
      EXPECT_EQ(s.material, 1u) << "opaque first " << opaque_first;
    }
  }
  {
    TriangleSoup soup;
    test::add_square(soup, 0.0f, -1.0f, 1.0f, 1);
    test::add_square(soup, 0.0f, -1.0f, 1.0f, 0);
    const std::vector<Material> materials{glass(1.5f, glm::vec3(0.0f)), glass(1.3f, glm::vec3(0.0f))};
    const ReferenceScene scene(soup, materials);
    for (const glm::vec3 o : {glm::vec3(0.3f, 1.0f, 0.2f), glm::vec3(-0.3f, 1.0f, -0.2f)}) {
      const SurfaceSample s = scene.intersect(o, glm::vec3(0.01f, -1.0f, 0.02f));
      EXPECT_LT(s.triangle, 2u);  // the lower pair
      EXPECT_EQ(s.material, 1u);
    }
  }
  // Two solids sharing a face (the plane x = 0, vertices of their own): a ray in the glass enters the flint
  // there before it leaves the glass, whichever comes first in the soup.
  for (int flint_first = 0; flint_first < 2; ++flint_first) {
    TriangleSoup soup;
    for (int k = 0; k < 2; ++k) {
      const bool flint = (k == 0) == (flint_first == 1);
      add_flat_box(soup, flint ? glm::vec3(0, -1, -1) : glm::vec3(-1, -1, -1),
                   flint ? glm::vec3(1, 1, 1) : glm::vec3(0, 1, 1), glm::mat3(1.0f), flint ? 1 : 0);
    }
    const std::vector<Material> materials{glass(1.5f, glm::vec3(0.0f)), glass(1.8f, glm::vec3(0.0f))};
    const ReferenceScene scene(soup, materials);
    const SurfaceSample s = scene.intersect(glm::vec3(-0.5f, 0.4f, 0.1f), glm::vec3(1.0f, -0.2f, 0.05f));
    ASSERT_NE(s.triangle, VOXR_NO_TRIANGLE);
    EXPECT_EQ(s.material, 1u) << "flint first " << flint_first;
    EXPECT_NEAR(s.position[0], 0.0f, 1e-5f);
  }
  const GlassOnFloor g;
  const ReferenceScene scene(g.soup, g.materials);
  // From the glass's top face down: the bottom face and the floor coincide; the floor is met.
  const glm::vec3 down(0.05f, -1.0f, 0.02f);
  const SurfaceSample top = scene.intersect(glm::vec3(0.1f, 2.0f, 0.2f), down);
  ASSERT_LT(top.triangle, 12u);
  EXPECT_NEAR(top.position[1], 0.8f, 1e-5f);
  const uint32_t left = top.triangle;
  const SurfaceSample bottom = scene.intersect_leaving(vec(top.position), down, std::span(&left, 1));
  EXPECT_GE(bottom.triangle, 12u);
  EXPECT_NEAR(bottom.distance, 0.8f * glm::length(glm::normalize(down) / glm::normalize(down).y), 1e-4f);
  // Leaving the floor up: the box's bottom face lies at distance ~0 and is met.
  const uint32_t floor = bottom.triangle;
  const SurfaceSample up =
      scene.intersect_leaving(vec(bottom.position), glm::vec3(0.0f, 1.0f, 0.1f), std::span(&floor, 1));
  ASSERT_LT(up.triangle, 12u);
  EXPECT_LT(up.distance, 1e-4f);
  EXPECT_THROW(scene.intersect_leaving(glm::vec3(0.0f), down, {}), Error);
}

// The box on a plane, seen from above: every ray into the glass reaches the floor under it
// (refracted down, or totally reflected off a side first); none ends in the environment under the floor.
// With the old rules (ties to the lowest id, then 1e-4 of the scene skipped after every surface) the
// bottom face, in the floor's very plane, won and handed its ray to a segment that skipped the floor:
// 5247 of these 5251 glass pixels escaped. Either new rule alone keeps the floor (the opaque one wins the
// tie; leaving the bottom face meets the floor at distance ~0); both are tested above. The full model
// agrees: with a black environment the glass pixels show the lit floor.
TEST(ReferenceRefraction, GlassOnFloorEndsOnTheFloor) {
  const GlassOnFloor g;
  const ReferenceScene scene(g.soup, g.materials);
  const CameraFrame camera = camera_at({0.13f, 3.0f, 0.07f}, {-0.05f, -1.0f, 0.03f}, 0.3f, 96);
  const EnvironmentMap black = EnvironmentMap::constant(glm::vec3(0.0f));
  const std::vector<RenderMaterial> mats = render_materials(g.materials);
  const RefractionReference matched =
      render_refraction_reference(scene, mats, light_from_above(), black, camera, ReferenceModel::kMatched);
  const RefractionReference full =
      render_refraction_reference(scene, mats, light_from_above(), black, camera, ReferenceModel::kFull);
  size_t glass_pixels = 0, in_environment = 0, on_floor = 0, dark = 0;
  for (size_t i = 0; i < matched.paths.size(); ++i) {
    if ((matched.paths[i].events & VOXR_PATH_EVENTS_MASK) == 0) continue;
    ++glass_pixels;
    in_environment += (matched.paths[i].events & VOXR_PATH_ENV) ? 1 : 0;
    on_floor += matched.ends[i].triangle >= 12 && matched.ends[i].triangle != VOXR_NO_TRIANGLE ? 1 : 0;
    const float m =
        std::max({matched.image.pixels[i].x, matched.image.pixels[i].y, matched.image.pixels[i].z});
    const float f = std::max({full.image.pixels[i].x, full.image.pixels[i].y, full.image.pixels[i].z});
    dark += m > 0.0f && f > 0.5f * m ? 0 : 1;
  }
  EXPECT_GT(glass_pixels, 3000u);
  EXPECT_EQ(in_environment, 0u);
  EXPECT_EQ(on_floor, glass_pixels);
  EXPECT_EQ(dark, 0u);
}

// A glass slab 1e-3 thick in a 20-unit scene (5e-5 of its size, above the merge distance of 1e-5 and
// under the 1e-4 the reference used to skip after every surface): every ray through it refracts twice.
TEST(ReferenceRefraction, ThinSlabRefractsTwice) {
  TriangleSoup soup;
  add_flat_box(soup, {-1, -1, -5e-4f}, {1, 1, 5e-4f},
               glm::mat3(glm::rotate(glm::mat4(1.0f), float(20.0 * kDegree), glm::vec3(0, 1, 0))), 0);
  soup.append(make_box({-10, -8, -10}, {10, -7, 10}), glm::mat4(1.0f), 1);  // far below: the scene's size
  const std::vector<Material> materials{glass(1.5f, glm::vec3(0.0f)), opaque()};
  const ReferenceScene scene(soup, materials);
  ASSERT_EQ(scene.scene_size(), 20.0f);
  const CameraFrame camera = camera_at({0.1f, 0.2f, 3}, {0, 0, -1}, 0.15f);
  const RefractionReference r =
      render_refraction_reference(scene, render_materials(materials), light_from_above(),
                                  EnvironmentMap::checker(64), camera, ReferenceModel::kMatched);
  for (const RefractionPath& q : r.paths) EXPECT_EQ(q.events, 2u | VOXR_PATH_ENV);
  EXPECT_LT(angle_deg(vec(r.paths[centre(camera)].exit_direction), camera.forward), 0.1);
}

RefractionPath path(uint32_t events, glm::vec3 exit_direction = glm::vec3(0, 0, -1)) {
  RefractionPath p{};
  p.events = events;
  for (int c = 0; c < 3; ++c) {
    p.throughput[c] = 1.0f;
    p.exit_direction[c] = exit_direction[c];
  }
  return p;
}

TEST(RefractionMetrics, HandMadePaths) {
  const uint32_t env = VOXR_PATH_ENV;
  // 0: both refract twice into the environment, exit directions 90 degrees apart.
  // 1: neither meets an interface.
  // 2: 2 against 3 interfaces (a mismatch), same exit direction: 0 degrees.
  // 3: a TIR in one only (a mismatch); the reference ends on a surface: no angle.
  const std::vector<RefractionPath> a{path(2 | env, {1, 0, 0}), path(0), path(2 | env),
                                      path(2 | VOXR_PATH_TIR | env)};
  const std::vector<RefractionPath> b{path(2 | env, {0, 2, 0}), path(0), path(3 | env), path(2)};
  ImageRgba image(2, 2, glm::vec4(0.5f, 0.5f, 0.5f, 1.0f)),
      reference(2, 2, glm::vec4(0.4f, 0.4f, 0.4f, 1.0f));
  RefractionError e = refraction_error(image, a, reference, b);
  EXPECT_NEAR(e.rmse, 0.1, 1e-6);
  EXPECT_NEAR(e.psnr, 20.0, 1e-4);
  EXPECT_EQ(e.angle_pixels, 2u);
  EXPECT_NEAR(e.angle_mean_deg, 45.0, 1e-9);
  EXPECT_NEAR(e.angle_p95_deg, 90.0, 1e-9);  // nearest rank of 2 values: the larger
  EXPECT_EQ(e.refracted_pixels, 3u);
  EXPECT_NEAR(e.event_mismatch_share, 2.0 / 3.0, 1e-12);
  EXPECT_EQ(e.nonfinite_pixels, 0u);

  // Small angles: atan2 keeps them (acos of the dot product would give 0).
  const std::vector<RefractionPath> c{path(1 | env, {0, 0, 1}), path(0), path(0), path(0)};
  const std::vector<RefractionPath> d{path(1 | env, {1e-5f, 0, 1}), path(0), path(0), path(0)};
  e = refraction_error(image, c, image, d);
  EXPECT_NEAR(e.angle_mean_deg, 1e-5 / kDegree, 1e-9);
  EXPECT_EQ(e.event_mismatch_share, 0.0);
  EXPECT_EQ(e.rmse, 0.0);

  // Non-finite pixels of the method's image.
  image.pixels[1].y = std::numeric_limits<float>::quiet_NaN();
  image.pixels[2].z = std::numeric_limits<float>::infinity();
  image.pixels[3].w = std::numeric_limits<float>::quiet_NaN();  // alpha does not count
  e = refraction_error(image, a, reference, b);
  EXPECT_EQ(e.nonfinite_pixels, 2u);

  // Sizes.
  EXPECT_THROW(refraction_error(ImageRgba(2, 1), a, reference, b), Error);
  EXPECT_THROW(refraction_error(image, std::span(a).first(3), reference, b), Error);
  EXPECT_THROW(refraction_error(image, a, reference, std::span(b).first(3)), Error);
}

// Issue 20, kind 6: a path cut short (VOXR_PATH_LOST, in the method's or the reference's) has no event
// sequence to compare: it is counted as lost and left out of the share, and a share over no compared pixel
// is NaN, not 0 %.
TEST(RefractionMetrics, LostPathsAreCountedNotCompared) {
  const uint32_t env = VOXR_PATH_ENV, lost = VOXR_PATH_LOST;
  const ImageRgba image(2, 2, glm::vec4(0.5f));
  // 0: the method lost the ray after one interface, the reference met one: compared, differing.
  // 1: the reference lost it: not compared.  2: 1 against 2 interfaces: a mismatch.  3: equal.
  const std::vector<RefractionPath> a{path(1 | lost), path(2 | env), path(1 | env), path(2 | env)};
  const std::vector<RefractionPath> b{path(1 | env), path(3 | lost), path(2 | env), path(2 | env)};
  RefractionError e = refraction_error(image, a, image, b);
  EXPECT_EQ(e.refracted_pixels, 4u);
  EXPECT_EQ(e.lost_pixels, 1u);
  EXPECT_EQ(e.method_lost_pixels, 1u);
  EXPECT_DOUBLE_EQ(e.event_mismatch_share, 2.0 / 3.0);
  // Every refracted pixel lost by the method (the camera-in-glass picture): every one differs, never 0 %.
  const std::vector<RefractionPath> all_lost(4, path(1 | lost)), reference(4, path(1 | env));
  e = refraction_error(image, all_lost, image, reference);
  EXPECT_EQ(e.method_lost_pixels, 4u);
  EXPECT_DOUBLE_EQ(e.event_mismatch_share, 1.0);
  // Every reference path lost: nothing compared, and the share says so (NaN), not 0 %.
  e = refraction_error(image, reference, image, all_lost);
  EXPECT_EQ(e.lost_pixels, 4u);
  EXPECT_TRUE(std::isnan(e.event_mismatch_share)) << e.event_mismatch_share;
}

// d_N from every vertex of a glass sphere is its diameter (the ray along -normal passes the centre to the
// antipodal vertex); an opaque box's vertices and an open glass square's (whose ray finds nothing) get -1
// (unknown).
TEST(InwardDistances, SphereDiameterOpaqueZero) {
  const float r = 0.75f;
  TriangleSoup soup = make_uv_sphere(r, 16, 32);
  const size_t sphere_vertices = soup.positions.size();
  soup.append(make_box({2, -0.5f, -0.5f}, {3, 0.5f, 0.5f}), glm::mat4(1.0f), 1);
  const size_t box_end = soup.positions.size();
  test::add_square(soup, 2.0f, 5.0f, 6.0f, 0);  // open glass, off to the side: its rays meet nothing
  const std::vector<Material> materials{glass(1.5f, glm::vec3(0.0f)), opaque()};
  const ReferenceScene scene(soup, materials);
  const std::vector<glm::vec3> normals = vertex_normals(soup);
  const std::vector<float> d = inward_distances(scene, soup, materials, normals);
  ASSERT_EQ(d.size(), soup.positions.size());
  for (size_t v = 0; v < sphere_vertices; ++v) EXPECT_NEAR(d[v], 2.0f * r, 0.01f * r) << "vertex " << v;
  for (size_t v = sphere_vertices; v < d.size(); ++v) EXPECT_EQ(d[v], -1.0f) << "vertex " << v;
  EXPECT_GT(d.size(), box_end);
  EXPECT_THROW(inward_distances(scene, soup, materials, std::vector<glm::vec3>(3)), Error);
}

}  // namespace
}  // namespace voxr
