// A glass ball of radius 1 (IOR 1.5, absorption (0.2, 0.1, 0.05)) at the origin seen by a camera on its
// axis, optionally with an opaque slab behind it: the analytic refraction scene the device methods' tests
// share (centre ray undeviated, throughput (1 - F)^2 exp(-2 sigma_a r)).
#pragma once

#include <glm/glm.hpp>

#include <cmath>
#include <vector>

#include "core/generators.h"
#include "core/material.h"
#include "core/triangle_soup.h"
#include "render/camera_frame.h"
#include "render/frame_renderer.h"
#include "render/scene_reference.h"
#include "util/error.h"
#include "voxr_layout.h"

#include <gtest/gtest.h>

namespace voxr::test::ball {

constexpr uint32_t kWidth = 97, kHeight = 73;  // odd: the centre pixel's ray passes through the ball's centre
constexpr float kRadius = 1.0f;
constexpr float kIor = 1.5f;
inline const glm::vec3 kAbsorption(0.2f, 0.1f, 0.05f);

inline CameraFrame camera() {
  CameraFrame f;
  f.eye = glm::vec3(0.0f, 0.0f, 4.0f);
  f.forward = glm::vec3(0.0f, 0.0f, -1.0f);
  f.right = glm::vec3(1.0f, 0.0f, 0.0f);
  f.up = glm::vec3(0.0f, 1.0f, 0.0f);
  f.tan_half_fov_y = std::tan(glm::radians(20.0f));
  f.width = kWidth;
  f.height = kHeight;
  f.near_plane = 0.1f;
  f.far_plane = 20.0f;
  return f;
}

inline RenderLight light() {
  RenderLight l{};
  l.directional = 1;
  const glm::vec3 d = glm::normalize(glm::vec3(0.3f, -1.0f, -0.5f));
  for (int a = 0; a < 3; ++a) {
    l.direction[a] = d[a];
    l.intensity[a] = 1.0f;
    l.ambient[a] = 0.2f;
  }
  return l;
}

inline std::vector<Material> materials() {
  Material glass;
  glass.name = "glass";
  glass.kind = MaterialKind::kDielectric;
  glass.ior = kIor;
  glass.absorption = kAbsorption;
  Material box;
  box.name = "box";
  box.kind = MaterialKind::kOpaque;
  box.color = glm::vec3(0.9f, 0.2f, 0.1f);
  return {glass, box};
}

constexpr uint32_t kGlass = 0, kBox = 1;

// The glass ball (material 0) at the origin, and with `box` an opaque slab (material 1) behind it.
inline TriangleSoup scene(bool box) {
  TriangleSoup soup;
  soup.append(make_uv_sphere(kRadius, 48, 96), glm::mat4(1.0f), kGlass);
  if (box)
    soup.append(make_box(glm::vec3(-2.0f, -2.0f, -3.0f), glm::vec3(2.0f, 2.0f, -2.5f)), glm::mat4(1.0f),
                kBox);
  return soup;
}

// d_N per vertex, analytic: a ball's chord along the inward normal through a surface point is its diameter
// (the tessellation's vertices lie on the sphere); elsewhere 0 (not used: the box is opaque).
inline std::vector<float> inward_distances(const TriangleSoup& soup) {
  std::vector<float> d(soup.vertex_count(), 0.0f);
  for (size_t v = 0; v < d.size(); ++v)
    if (std::abs(glm::length(glm::vec3(soup.positions[v])) - kRadius) < 1e-4f) d[v] = 2.0f * kRadius;
  return d;
}

// A SceneReference that knows only d_N (given, e.g. the analytic one above; empty: unknown everywhere): what
// image-space refraction asks in its per-scene setup. Every other question fails the test.
class FixedInwardDistances final : public SceneReference {
 public:
  explicit FixedInwardDistances(std::vector<float> d_n) : d_n_(std::move(d_n)) {}
  std::vector<glm::vec3> transmittance(const RenderLight&, std::span<const SurfaceSample>) override {
    throw InternalError("FixedInwardDistances has no transmittance");
  }
  std::vector<float> inward_distances(const std::vector<glm::vec3>&) override { return d_n_; }
  HostRefraction refraction(const RenderLight&, const EnvironmentMap&, const CameraFrame&, bool) override {
    throw InternalError("FixedInwardDistances has no refraction");
  }
  double build_ms() const override { return 0.0; }

 private:
  std::vector<float> d_n_;
};

inline glm::vec3 vec(const float (&a)[3]) {
  return glm::vec3(a[0], a[1], a[2]);
}

inline bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

inline void expect_all_finite(const RenderedFrame& frame) {
  size_t bad = 0;
  for (const glm::vec4& p : frame.image.pixels) bad += !finite(glm::vec3(p));
  for (const RefractionPath& p : frame.paths)
    bad += !finite(vec(p.throughput)) || !finite(vec(p.exit_direction)) || !finite(vec(p.exit_position));
  EXPECT_EQ(bad, 0u) << "pixels or paths with NaN or infinity";
}

inline size_t centre_pixel() {
  return size_t(kHeight / 2) * kWidth + kWidth / 2;
}

}  // namespace voxr::test::ball
