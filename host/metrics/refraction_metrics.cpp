#include "metrics/refraction_metrics.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "metrics/image_metrics.h"
#include "util/error.h"

namespace voxr {

namespace {

uint32_t interfaces(const RefractionPath& p) {
  return p.events & VOXR_PATH_EVENTS_MASK;
}

// Angle between a and b in degrees, atan2(|a x b|, a . b) in double: accurate at small angles, where acos
// of the dot product loses half the digits. Need not be unit.
double angle_deg(const float* a, const float* b) {
  const glm::dvec3 u(a[0], a[1], a[2]), v(b[0], b[1], b[2]);
  return std::atan2(glm::length(glm::cross(u, v)), glm::dot(u, v)) * (180.0 / 3.14159265358979323846);
}

}  // namespace

RefractionError refraction_error(const ImageRgba& image, std::span<const RefractionPath> paths,
                                 const ImageRgba& reference,
                                 std::span<const RefractionPath> reference_paths) {
  if (image.width != reference.width || image.height != reference.height)
    fail("refraction error: the image is {}x{} but the reference is {}x{}", image.width, image.height,
         reference.width, reference.height);
  const size_t pixels = size_t(reference.width) * reference.height;
  if (image.pixels.size() != pixels || reference.pixels.size() != pixels)
    fail("refraction error: {} and {} pixels for a {}x{} image", image.pixels.size(), reference.pixels.size(),
         reference.width, reference.height);
  if (paths.size() != pixels || reference_paths.size() != pixels)
    fail("refraction error: {} paths and {} reference paths for a {}x{} image", paths.size(),
         reference_paths.size(), reference.width, reference.height);

  RefractionError e;
  e.rmse = rmse(image, reference);
  e.psnr = psnr(image, reference);

  std::vector<double> angles;
  uint64_t mismatches = 0;
  for (size_t i = 0; i < pixels; ++i) {
    const RefractionPath &a = paths[i], &b = reference_paths[i];
    const uint32_t na = interfaces(a), nb = interfaces(b);
    if (na == 0 && nb == 0) continue;
    ++e.refracted_pixels;
    if (b.events & VOXR_PATH_LOST) {
      ++e.lost_pixels;
      continue;
    }
    if (a.events & VOXR_PATH_LOST) {
      ++e.method_lost_pixels;
      ++mismatches;
      continue;
    }
    if (na != nb || (a.events & VOXR_PATH_TIR) != (b.events & VOXR_PATH_TIR)) ++mismatches;
    if (na > 0 && nb > 0 && (a.events & VOXR_PATH_ENV) && (b.events & VOXR_PATH_ENV))
      angles.push_back(angle_deg(a.exit_direction, b.exit_direction));
  }
  const uint64_t compared = e.refracted_pixels - e.lost_pixels;
  e.event_mismatch_share =
      compared > 0 ? double(mismatches) / double(compared) : std::numeric_limits<double>::quiet_NaN();

  e.angle_pixels = angles.size();
  if (!angles.empty()) {
    if (std::any_of(angles.begin(), angles.end(), [](double a) { return !std::isfinite(a); })) {
      // A non-finite exit direction: no meaningful statistic (and no sorting of NaNs).
      e.angle_mean_deg = e.angle_p95_deg = std::numeric_limits<double>::quiet_NaN();
    } else {
      double sum = 0.0;
      for (double a : angles) sum += a;
      e.angle_mean_deg = sum / double(angles.size());
      // Nearest rank: the smallest value with at least 95 % of the values at or below it.
      const size_t rank = size_t(std::ceil(0.95 * double(angles.size())));
      const size_t index = std::max<size_t>(rank, 1) - 1;
      std::nth_element(angles.begin(), angles.begin() + ptrdiff_t(index), angles.end());
      e.angle_p95_deg = angles[index];
    }
  }

  for (const glm::vec4& p : image.pixels)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) ++e.nonfinite_pixels;
  return e;
}

}  // namespace voxr
