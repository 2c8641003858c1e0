// Image and transmittance metrics against values computed by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "metrics/image_metrics.h"
#include "util/error.h"

namespace voxr {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// 2x1 images whose RGB values differ by 0.3 (pixel 0, blue) and 0.4 (pixel 1, green): squared error
// 0.09 + 0.16 = 0.25 over 6 values. Alpha differs too and must not count.
ImageRgba left() {
  ImageRgba image(2, 1);
  image.at(0, 0) = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  image.at(1, 0) = glm::vec4(1.0f, 1.0f, 1.0f, 1.0f);
  return image;
}
ImageRgba right() {
  ImageRgba image(2, 1);
  image.at(0, 0) = glm::vec4(0.0f, 0.0f, 0.3f, 0.0f);
  image.at(1, 0) = glm::vec4(1.0f, 0.6f, 1.0f, 0.5f);
  return image;
}

void expect_rgb(const glm::vec4& pixel, glm::vec3 rgb) {
  EXPECT_NEAR(pixel.x, rgb.x, 1e-6f);
  EXPECT_NEAR(pixel.y, rgb.y, 1e-6f);
  EXPECT_NEAR(pixel.z, rgb.z, 1e-6f);
  EXPECT_EQ(pixel.w, 1.0f);
}

TEST(ImageMetrics, RmseOverRgbValues) {
  EXPECT_NEAR(rmse(left(), right()), std::sqrt(0.25 / 6.0), 1e-7);  // 0.2041241
  EXPECT_NEAR(rmse(right(), left()), std::sqrt(0.25 / 6.0), 1e-7);
  EXPECT_EQ(rmse(left(), left()), 0.0);
  EXPECT_EQ(rmse(ImageRgba(), ImageRgba()), 0.0);
  ImageRgba nan = left();
  nan.at(0, 0).y = kNaN;
  EXPECT_TRUE(std::isnan(rmse(nan, left())));
  EXPECT_THROW(rmse(left(), ImageRgba(1, 2)), Error);
}

TEST(ImageMetrics, PsnrFromTheSameMse) {
  EXPECT_NEAR(psnr(left(), right()), 10.0 * std::log10(24.0), 1e-6);       // 13.80 dB: MSE 1/24
  EXPECT_NEAR(psnr(left(), right(), 2.0), 10.0 * std::log10(96.0), 1e-6);  // peak^2 = 4
  EXPECT_EQ(psnr(left(), left()), std::numeric_limits<double>::infinity());
  EXPECT_THROW(psnr(left(), right(), 0.0), Error);
  EXPECT_THROW(psnr(left(), ImageRgba(2, 2)), Error);
}

TEST(ImageMetrics, TransmittanceErrorAtReceivers) {
  // Pixel 0: exact. Pixel 1: off by (0.1, 0, -0.04), over the threshold. Pixel 2: far off but not a receiver.
  // Pixel 3: off by 0.03 in every channel, under the threshold.
  const std::vector<glm::vec3> actual{
      {0.5f, 0.5f, 0.5f}, {0.4f, 0.6f, 0.86f}, {1, 1, 1}, {0.33f, 0.53f, 0.73f}};
  const std::vector<glm::vec3> reference{
      {0.5f, 0.5f, 0.5f}, {0.3f, 0.6f, 0.9f}, {0, 0, 0}, {0.3f, 0.5f, 0.7f}};
  const std::vector<uint8_t> mask{1, 1, 0, 255};
  const TransmittanceError e = transmittance_error(actual, reference, mask);
  EXPECT_EQ(e.receivers, 3u);
  // (0.01 + 0.0016 + 3 * 0.0009) / 9 values = 0.0143 / 9.
  EXPECT_NEAR(e.rmse, std::sqrt(0.0143 / 9.0), 1e-6);
  EXPECT_NEAR(e.max_abs, 0.1, 1e-6);
  EXPECT_NEAR(e.share_over_threshold, 1.0 / 3.0, 1e-12);
  // A looser threshold passes pixel 1 too; a tighter one catches pixel 3.
  EXPECT_EQ(transmittance_error(actual, reference, mask, 0.2).share_over_threshold, 0.0);
  EXPECT_NEAR(transmittance_error(actual, reference, mask, 0.01).share_over_threshold, 2.0 / 3.0, 1e-12);
}

TEST(ImageMetrics, TransmittanceErrorEdgeCases) {
  const std::vector<glm::vec3> a{{1, 1, 1}, {kNaN, 0, 0}}, b{{0, 0, 0}, {0, 0, 0}};
  // No receivers: all zero.
  const TransmittanceError none = transmittance_error(a, b, std::vector<uint8_t>{0, 0});
  EXPECT_EQ(none.receivers, 0u);
  EXPECT_EQ(none.rmse, 0.0);
  EXPECT_EQ(none.max_abs, 0.0);
  EXPECT_EQ(none.share_over_threshold, 0.0);
  // A NaN at a receiver poisons the RMSE and the maximum and counts as over the threshold.
  const TransmittanceError nan = transmittance_error(a, b, std::vector<uint8_t>{0, 1});
  EXPECT_TRUE(std::isnan(nan.rmse));
  EXPECT_TRUE(std::isnan(nan.max_abs));
  EXPECT_EQ(nan.share_over_threshold, 1.0);
  EXPECT_THROW(transmittance_error(a, b, std::vector<uint8_t>{1}), Error);
  EXPECT_THROW(transmittance_error(a, std::vector<glm::vec3>{{0, 0, 0}}, std::vector<uint8_t>{1, 1}), Error);
}

TEST(ImageMetrics, ErrorImageIsAHeatMap) {
  // Largest channel errors 0, 0.5 and 1 (and NaN).
  ImageRgba a(4, 1), b(4, 1);
  a.at(1, 0) = glm::vec4(0.2f, 0.5f, 0.0f, 1.0f);
  a.at(2, 0) = glm::vec4(0.0f, 0.0f, 1.0f, 1.0f);
  a.at(3, 0) = glm::vec4(kNaN, 0.0f, 0.0f, 1.0f);
  const ImageRgba scaled = error_image(a, b);  // full scale = the largest error, 1
  ASSERT_EQ(scaled.width, 4u);
  ASSERT_EQ(scaled.height, 1u);
  expect_rgb(scaled.at(0, 0), {0, 0, 0});     // black
  expect_rgb(scaled.at(1, 0), {1, 0.5f, 0});  // half way: between red and yellow
  expect_rgb(scaled.at(2, 0), {1, 1, 1});     // white
  expect_rgb(scaled.at(3, 0), {1, 0, 1});     // NaN: magenta
  const ImageRgba fixed = error_image(a, b, 3.0);
  expect_rgb(fixed.at(1, 0), {0.5f, 0, 0});  // 0.5 / 3 = 1/6: half-way to red
  expect_rgb(fixed.at(2, 0), {1, 0, 0});     // 1 / 3: red
  // Identical images: all black.
  for (const glm::vec4& p : error_image(b, b).pixels) expect_rgb(p, {0, 0, 0});
  EXPECT_THROW(error_image(a, ImageRgba(2, 2)), Error);
}

TEST(ImageMetrics, TransmittanceErrorImageGreysNonReceivers) {
  const std::vector<glm::vec3> actual{{0.5f, 0.5f, 0.5f}, {1, 1, 1}, {0.25f, 0.5f, 0.5f}, {0, 0, 0}};
  const std::vector<glm::vec3> reference(4, glm::vec3(0.5f));
  const std::vector<uint8_t> mask{1, 0, 1, 1};
  // Receiver errors 0, 0.25, 0.5: the largest (0.5) is white; pixel 1's error of 0.5 is not counted.
  const ImageRgba image = error_image(actual, reference, 2, 2, mask);
  expect_rgb(image.at(0, 0), {0, 0, 0});
  expect_rgb(image.at(1, 0), {0.1f, 0.1f, 0.1f});
  expect_rgb(image.at(0, 1), {1, 0.5f, 0});
  expect_rgb(image.at(1, 1), {1, 1, 1});
  // Without a mask every pixel counts.
  expect_rgb(error_image(actual, reference, 2, 2).at(1, 0), {1, 1, 1});
  EXPECT_THROW(error_image(actual, reference, 3, 1), Error);
  EXPECT_THROW(error_image(actual, reference, 2, 2, std::vector<uint8_t>{1}), Error);
}

}  // namespace
}  // namespace voxr
