// How far a refraction method's image and paths are from the reference's (DESIGN.md, metrics): one
// definition of each number, used by `voxr render --compare-reference`, the benchmark and the tests.
#pragma once

#include <cstdint>
#include <span>

#include "util/image_rgba.h"
#include "voxr_layout.h"

namespace voxr {

struct RefractionError {
  double rmse = 0.0;  // image RMSE over every pixel and RGB channel (metrics/image_metrics.h rmse)
  double psnr = 0.0;  // dB, peak 1 (image_metrics.h psnr)
  // Exit direction: angle between the two paths' exit_direction, in degrees, over pixels where both paths
  // met at least one interface and both end in the environment (VOXR_PATH_ENV).
  // p95: nearest rank (the smallest angle with at least 95 % of them at or below it). Angles are
  // atan2(|a x b|, a . b) in double. Both are 0 when there are no such pixels, NaN when an exit direction
  // is not finite.
  double angle_mean_deg = 0.0, angle_p95_deg = 0.0;
  uint64_t angle_pixels = 0;
  // Pixels where either path met an interface; of them, those whose reference path is VOXR_PATH_LOST (cut
  // short by a limit: no event sequence to compare with, so not compared), those the method alone lost
  // (compared, and counted as differing: a method that loses a path has not followed the reference's); and
  // the share of the compared ones (refracted - lost) whose event sequence differs: the number of interfaces
  // (events & VOXR_PATH_EVENTS_MASK), whether there was a total internal reflection, or the method's path
  // lost. The share is NaN when no pixel could be compared (never 0 % over nothing).
  uint64_t refracted_pixels = 0;
  uint64_t lost_pixels = 0;         // the reference's path lost: not compared
  uint64_t method_lost_pixels = 0;  // the method's path lost where the reference's is not: differing
  double event_mismatch_share = 0.0;
  uint64_t nonfinite_pixels = 0;  // pixels of `image` with a NaN or infinite channel (must be 0)
};

// `image` and `paths` (the method's) against `reference` and `reference_paths` (the matched reference's),
// all width * height. Throws voxr::Error when the sizes differ.
RefractionError refraction_error(const ImageRgba& image, std::span<const RefractionPath> paths,
                                 const ImageRgba& reference, std::span<const RefractionPath> reference_paths);

}  // namespace voxr
