#include "metrics/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "util/error.h"

namespace voxr {

namespace {

void check_same_size(const ImageRgba& a, const ImageRgba& b, const char* what) {
  if (a.width != b.width || a.height != b.height)
    fail("{}: images differ in size ({}x{} vs {}x{})", what, a.width, a.height, b.width, b.height);
}

// Sum of squared RGB differences over all pixels.
double squared_error(const ImageRgba& a, const ImageRgba& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double d = double(a.pixels[i][c]) - double(b.pixels[i][c]);
      sum += d * d;
    }
  return sum;
}

// Largest |difference| over R, G and B (NaN when any is NaN).
double max_channel_difference(const glm::vec3& a, const glm::vec3& b) {
  double m = 0.0;
  for (int c = 0; c < 3; ++c) {
    const double d = std::abs(double(a[c]) - double(b[c]));
    if (std::isnan(d)) return d;
    m = std::max(m, d);
  }
  return m;
}

// Black (0) -> red (1/3) -> yellow (2/3) -> white (1); magenta for NaN.
glm::vec4 heat(double t) {
  if (std::isnan(t)) return glm::vec4(1.0f, 0.0f, 1.0f, 1.0f);
  const float s = float(3.0 * std::clamp(t, 0.0, 1.0));
  return glm::vec4(std::clamp(s, 0.0f, 1.0f), std::clamp(s - 1.0f, 0.0f, 1.0f),
                   std::clamp(s - 2.0f, 0.0f, 1.0f), 1.0f);
}

std::vector<glm::vec3> rgb(const ImageRgba& image) {
  std::vector<glm::vec3> out(image.pixels.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = glm::vec3(image.pixels[i]);
  return out;
}

}  // namespace

double rmse(const ImageRgba& a, const ImageRgba& b) {
  check_same_size(a, b, "rmse");
  if (a.pixels.empty()) return 0.0;
  return std::sqrt(squared_error(a, b) / (3.0 * double(a.pixels.size())));
}

double psnr(const ImageRgba& a, const ImageRgba& b, double peak) {
  check_same_size(a, b, "psnr");
  if (!(peak > 0.0)) fail("psnr: peak must be positive (got {})", peak);
  const double mse = a.pixels.empty() ? 0.0 : squared_error(a, b) / (3.0 * double(a.pixels.size()));
  if (mse == 0.0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(peak * peak / mse);
}

TransmittanceError transmittance_error(std::span<const glm::vec3> actual,
                                       std::span<const glm::vec3> reference,
                                       std::span<const uint8_t> receiver_mask, double threshold) {
  if (actual.size() != reference.size() || actual.size() != receiver_mask.size())
    fail("transmittance_error: {} values, {} reference values and {} mask bytes (all must be equal)",
         actual.size(), reference.size(), receiver_mask.size());
  TransmittanceError e;
  double sum = 0.0;
  uint64_t over = 0;
  for (size_t i = 0; i < actual.size(); ++i) {
    if (!receiver_mask[i]) continue;
    ++e.receivers;
    for (int c = 0; c < 3; ++c) {
      const double d = double(actual[i][c]) - double(reference[i][c]);
      sum += d * d;
    }
    const double m = max_channel_difference(actual[i], reference[i]);
    // NaN propagates into max_abs (std::max would drop it) and counts as over the threshold.
    e.max_abs = std::isnan(m) || std::isnan(e.max_abs) ? std::numeric_limits<double>::quiet_NaN()
                                                       : std::max(e.max_abs, m);
    over += !(m <= threshold);
  }
  if (e.receivers == 0) return e;
  e.rmse = std::sqrt(sum / (3.0 * double(e.receivers)));
  e.share_over_threshold = double(over) / double(e.receivers);
  return e;
}

ImageRgba error_image(const ImageRgba& actual, const ImageRgba& reference, double full_scale) {
  check_same_size(actual, reference, "error_image");
  const std::vector<glm::vec3> a = rgb(actual), b = rgb(reference);
  return error_image(a, b, actual.width, actual.height, {}, full_scale);
}

ImageRgba error_image(std::span<const glm::vec3> actual, std::span<const glm::vec3> reference, uint32_t width,
                      uint32_t height, std::span<const uint8_t> receiver_mask, double full_scale) {
  const size_t n = size_t(width) * height;
  if (actual.size() != n || reference.size() != n || (!receiver_mask.empty() && receiver_mask.size() != n))
    fail("error_image: a {}x{} image needs {} values (got {}, {} reference values and {} mask bytes)", width,
         height, n, actual.size(), reference.size(), receiver_mask.size());
  auto counted = [&](size_t i) { return receiver_mask.empty() || receiver_mask[i] != 0; };
  std::vector<double> error(n, 0.0);
  double largest = 0.0;
  for (size_t i = 0; i < n; ++i) {
    if (!counted(i)) continue;
    error[i] = max_channel_difference(actual[i], reference[i]);
    if (!std::isnan(error[i])) largest = std::max(largest, error[i]);
  }
  const double scale = full_scale > 0.0 ? full_scale : largest > 0.0 ? largest : 1.0;
  ImageRgba out(width, height);
  for (size_t i = 0; i < n; ++i)
    out.pixels[i] = counted(i) ? heat(error[i] / scale) : glm::vec4(0.1f, 0.1f, 0.1f, 1.0f);
  return out;
}

}  // namespace voxr
