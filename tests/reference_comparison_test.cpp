// eval/reference_comparison.h: measure_against_reference on hand-made 2x2 frames (no device, no Embree): a
// frame equal to the exact one has no error, and a known perturbation gives the error computed by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "eval/reference_comparison.h"
#include "util/error.h"

namespace voxr {
namespace {

constexpr uint32_t kWidth = 2, kHeight = 2;

// A path that met `interfaces` interfaces and leaves to the environment along +z.
RefractionPath path(uint32_t interfaces) {
  RefractionPath p{};
  p.events = interfaces | VOXR_PATH_ENV;
  p.throughput[0] = p.throughput[1] = p.throughput[2] = 1.0f;
  p.exit_direction[2] = 1.0f;
  return p;
}

// The exact frame: shadows (transmittance 1 everywhere, receivers all but pixel 2, image grey 0.5) and the
// matched refraction (image grey 0.25, pixel 0 refracted twice).
ReferenceFrame exact_frame() {
  ReferenceFrame r;
  ExactShadows s;
  s.transmittance.assign(kWidth * kHeight, glm::vec3(1.0f));
  s.receivers = {1, 1, 0, 1};
  s.image = ImageRgba(kWidth, kHeight, glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
  r.shadows = std::move(s);
  RefractionReference m;
  m.image = ImageRgba(kWidth, kHeight, glm::vec4(0.25f, 0.25f, 0.25f, 1.0f));
  m.paths = {path(2), path(0), path(0), path(0)};
  r.refraction = std::move(m);
  return r;
}

// The frame the exact one would be: its image the shadows' image, its transmittance and paths the exact ones.
RenderedFrame equal_frame(const ReferenceFrame& r) {
  RenderedFrame f;
  f.image = r.shadows->image;
  f.transmittance = r.shadows->transmittance;
  f.paths = r.refraction->paths;
  return f;
}

TEST(ReferenceComparison, EqualFrameHasNoError) {
  ReferenceFrame r = exact_frame();
  r.refraction->image = r.shadows->image;  // the frame's paths with exact shadows are the reference's
  const FrameError e = measure_against_reference(equal_frame(r), r);
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(e.image_rmse, 0.0);
  EXPECT_EQ(e.image_psnr, inf);
  ASSERT_TRUE(e.shadows);
  EXPECT_EQ(e.shadows->transmittance.rmse, 0.0);
  EXPECT_EQ(e.shadows->transmittance.max_abs, 0.0);
  EXPECT_EQ(e.shadows->transmittance.share_over_threshold, 0.0);
  EXPECT_EQ(e.shadows->transmittance.receivers, 3u);
  EXPECT_EQ(e.shadows->psnr, inf);
  ASSERT_TRUE(e.refraction);
  EXPECT_EQ(e.refraction->rmse, 0.0);
  EXPECT_EQ(e.refraction->psnr, inf);
  EXPECT_EQ(e.refraction->refracted_pixels, 1u);
  EXPECT_EQ(e.refraction->event_mismatch_share, 0.0);
  EXPECT_EQ(e.refraction->angle_mean_deg, 0.0);
  EXPECT_EQ(e.refraction->nonfinite_pixels, 0u);
}

TEST(ReferenceComparison, KnownPerturbationGivesItsError) {
  const ReferenceFrame r = exact_frame();
  RenderedFrame f = equal_frame(r);
  f.image.pixels[1].x += 0.1f;           // one of 12 values off by 0.1
  f.transmittance[0].x -= 0.1f;          // a receiver: off by 0.1, over the 0.05 threshold
  f.transmittance[2] = glm::vec3(0.0f);  // not a receiver: not counted
  f.paths[0] = path(1);                  // refracted once where the reference refracts twice
  const FrameError e = measure_against_reference(f, r);
  // Image against the refraction reference (0.25): 11 values off by 0.25, one by 0.35.
  const double image_mse = (11.0 * 0.25 * 0.25 + 0.35 * 0.35) / 12.0;
  EXPECT_NEAR(e.image_rmse, std::sqrt(image_mse), 1e-7);
  EXPECT_NEAR(e.image_psnr, 10.0 * std::log10(1.0 / image_mse), 1e-5);
  ASSERT_TRUE(e.shadows);
  // 3 receivers x 3 channels, one value off by 0.1.
  EXPECT_NEAR(e.shadows->transmittance.rmse, std::sqrt(0.01 / 9.0), 1e-7);
  EXPECT_NEAR(e.shadows->transmittance.max_abs, 0.1, 1e-7);
  EXPECT_NEAR(e.shadows->transmittance.share_over_threshold, 1.0 / 3.0, 1e-12);
  EXPECT_EQ(e.shadows->transmittance.receivers, 3u);
  // The image against the shadows' image (0.5): one of 12 values off by 0.1.
  EXPECT_NEAR(e.shadows->psnr, 10.0 * std::log10(12.0 / 0.01), 1e-4);
  ASSERT_TRUE(e.refraction);
  // With exact shadows in the reference, the refraction is measured on their image (0.5 against 0.25), not
  // on the frame's perturbed one.
  EXPECT_NEAR(e.refraction->rmse, 0.25, 1e-7);
  EXPECT_EQ(e.refraction->refracted_pixels, 1u);
  EXPECT_EQ(e.refraction->event_mismatch_share, 1.0);
}

TEST(ReferenceComparison, WithoutExactShadowsRefractionReadsTheFrameImage) {
  ReferenceFrame r = exact_frame();
  r.shadows.reset();
  RenderedFrame f;
  f.image = r.refraction->image;
  f.image.pixels[3].z += 0.2f;  // one of 12 values off by 0.2
  f.paths = r.refraction->paths;
  f.transmittance.assign(kWidth * kHeight, glm::vec3(1.0f));
  const FrameError e = measure_against_reference(f, r);
  EXPECT_FALSE(e.shadows);
  ASSERT_TRUE(e.refraction);
  EXPECT_NEAR(e.refraction->rmse, std::sqrt(0.04 / 12.0), 1e-7);
  EXPECT_NEAR(e.image_rmse, e.refraction->rmse, 1e-12);
  EXPECT_EQ(e.refraction->event_mismatch_share, 0.0);
}

TEST(ReferenceComparison, PartsNeedWhatTheFrameKept) {
  const ReferenceFrame r = exact_frame();
  RenderedFrame f;  // keep_samples off: the image alone
  f.image = r.refraction->image;
  const FrameError e = measure_against_reference(f, r);
  EXPECT_EQ(e.image_rmse, 0.0);
  EXPECT_FALSE(e.shadows);
  EXPECT_FALSE(e.refraction);
  EXPECT_THROW(measure_against_reference(f, ReferenceFrame{}), Error);
  f.image = ImageRgba(1, 1);
  EXPECT_THROW(measure_against_reference(f, r), Error);
}

}  // namespace
}  // namespace voxr
