// Whole frames on the device against the Embree reference at the same receiver points: every shadow method's
// transmittance error on small scenes, the methods' order where the sources say one beats the other, and
// determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/default_scene.h"
#include "core/generators.h"
#include "metrics/image_metrics.h"
#include "metrics/shadow_receivers.h"
#include "reference/reference_scene.h"
#include "render/environment_map.h"
#include "render/frame_renderer.h"
#include "render/render_scene.h"
#include "test_support.h"

namespace voxr {
namespace {

struct Measured {
  TransmittanceError error;
  bool finite = true;
};

class Frames {
 public:
  explicit Frames(Scene scene, uint32_t width = 96, uint32_t height = 72)
      : materials_(scene.materials), soup_(take_scene_triangles(scene)), renderer_(test::runtime()) {
    camera_ = make_camera_frame(scene.camera, soup_.anchor, soup_.bounds(), width, height);
    light_ = render_light(scene.light, make_environment_map(scene.environment).mean(), soup_.anchor);
    renderer_.set_scene(soup_, materials_);
    RenderOptions none;
    none.shadows = ShadowMethod::kNone;
    none.keep_samples = true;
    renderer_.prepare(none);
    base_ = renderer_.render(light_, camera_, none);
    ReferenceScene reference(soup_, materials_);
    exact_ = reference.transmittance(light_, base_.samples);
    mask_ = shadow_receivers(base_.samples, render_materials(materials_), light_);
  }

  Measured measure(RenderOptions o) {
    o.keep_samples = true;
    renderer_.prepare(o);
    const RenderedFrame f = renderer_.render(light_, camera_, o);
    Measured m;
    m.error = transmittance_error(f.transmittance, exact_, mask_, 0.05);
    for (const glm::vec4& p : f.image.pixels)
      m.finite = m.finite && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
    return m;
  }
  RenderedFrame render(RenderOptions o) {
    renderer_.prepare(o);
    return renderer_.render(light_, camera_, o);
  }
  uint64_t receivers() const { return std::count(mask_.begin(), mask_.end(), uint8_t(1)); }

 private:
  std::vector<Material> materials_;
  TriangleSoup soup_;
  FrameRenderer renderer_;
  CameraFrame camera_;
  RenderLight light_;
  RenderedFrame base_;
  std::vector<glm::vec3> exact_;
  std::vector<uint8_t> mask_;
};

RenderOptions method(ShadowMethod m, uint32_t res, RasterMode mode = RasterMode::kCenter) {
  RenderOptions o;
  o.shadows = m;
  o.shadow_resolution = res;
  o.mode = mode;
  return o;
}

TEST(FrameRenderer, DefaultSceneEveryMethodAgainstTheReference) {
  Frames frames(default_scene());
  ASSERT_GT(frames.receivers(), 2000u);
  const Measured voxel = frames.measure(method(ShadowMethod::kVoxel, 128));
  const Measured conservative = frames.measure(method(ShadowMethod::kVoxel, 128, RasterMode::kConservative));
  const Measured uniform = frames.measure(method(ShadowMethod::kUniform, 128));
  const Measured filter = frames.measure(method(ShadowMethod::kFilter, 128));
  const Measured opaque = frames.measure(method(ShadowMethod::kOpaque, 128));
  const Measured none = frames.measure(method(ShadowMethod::kNone, 128));
  for (const Measured* m : {&voxel, &conservative, &uniform, &filter, &opaque, &none}) EXPECT_TRUE(m->finite);
  // Bounds measured on PoCL with some slack (bench/results/shadows-*.md has the full table).
  EXPECT_LT(voxel.error.rmse, 0.06);
  EXPECT_LT(voxel.error.rmse, uniform.error.rmse);
  EXPECT_LT(voxel.error.rmse, opaque.error.rmse);
  EXPECT_LT(voxel.error.rmse, none.error.rmse);
  EXPECT_LT(voxel.error.rmse, conservative.error.rmse);
}

TEST(FrameRenderer, ErrorFallsAsTheShadowGridGrows) {
  Frames frames(default_scene());
  const double coarse = frames.measure(method(ShadowMethod::kVoxel, 32)).error.rmse;
  const double fine = frames.measure(method(ShadowMethod::kVoxel, 256)).error.rmse;
  EXPECT_LT(fine, coarse);
}

TEST(FrameRenderer, FramesAreDeterministic) {
  Frames frames(default_scene(), 64, 48);
  for (ShadowMethod m :
       {ShadowMethod::kVoxel, ShadowMethod::kUniform, ShadowMethod::kFilter, ShadowMethod::kOpaque}) {
    const RenderedFrame a = frames.render(method(m, 64));
    const RenderedFrame b = frames.render(method(m, 64));
    EXPECT_EQ(a.image.pixels, b.image.pixels) << shadow_method_info(m).name;
  }
}

}  // namespace
}  // namespace voxr
