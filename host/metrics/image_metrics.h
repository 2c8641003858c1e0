// Image and shadow-transmittance errors (DESIGN.md, "Metrics"): one definition each, used by the tests'
// render regression harness, the benchmarks and the reports. Values are linear (no sRGB), alpha is ignored.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <span>

#include "util/image_rgba.h"

namespace voxr {

// Root mean square of the differences over the R, G and B values of every pixel (3 * width * height
// values). Throws voxr::Error when the sizes differ. 0 for two empty images; NaN when a value is NaN.
double rmse(const ImageRgba& a, const ImageRgba& b);

// Peak signal-to-noise ratio in dB, 10 log10(peak^2 / MSE) with the MSE of rmse(); +infinity when the
// images are equal. Needs peak > 0; throws voxr::Error when the sizes differ.
double psnr(const ImageRgba& a, const ImageRgba& b, double peak = 1.0);

// Shadow transmittance at the receivers (the pixels whose mask byte is non-zero) against the reference.
struct TransmittanceError {
  double rmse = 0.0;                  // over the R, G and B values of the receivers
  double max_abs = 0.0;               // largest |difference| of any channel of any receiver
  double share_over_threshold = 0.0;  // receivers whose largest channel |difference| exceeds the threshold
  uint64_t receivers = 0;  // mask bytes that are non-zero (all the above are 0 when there are none)
};

// One value per pixel in each span (same length, else voxr::Error). A NaN at a receiver makes rmse and
// max_abs NaN and counts as over the threshold.
TransmittanceError transmittance_error(std::span<const glm::vec3> actual,
                                       std::span<const glm::vec3> reference,
                                       std::span<const uint8_t> receiver_mask, double threshold = 0.05);

// Heat map of the per-pixel error (the largest |difference| over R, G and B): black at 0 through red and
// yellow to white at `full_scale` and above; alpha 1. full_scale <= 0 scales to the image's largest error (or
// 1 when all are 0). NaN errors show as magenta. Throws voxr::Error when the sizes differ.
ImageRgba error_image(const ImageRgba& actual, const ImageRgba& reference, double full_scale = 0.0);

// The same for transmittance values of a width x height image (row-major, top row first); pixels outside
// `receiver_mask` (when given, one byte per pixel) show as dark grey (0.1). Throws voxr::Error when a
// span's length is not width * height.
ImageRgba error_image(std::span<const glm::vec3> actual, std::span<const glm::vec3> reference, uint32_t width,
                      uint32_t height, std::span<const uint8_t> receiver_mask = {}, double full_scale = 0.0);

}  // namespace voxr
