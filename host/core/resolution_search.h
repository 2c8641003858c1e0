// "Model no more than a scene needs" (issue 11): the smallest grid resolution whose measured error is at most
// a target, for `voxr voxelize --error-target` (surface error) and `voxr render --error-target` (image
// error).
//
// How: measure at the lowest resolution; while the target is not met, predict the resolution that meets it
// from the last miss assuming error falls as 1 / resolution (a surface voxelization's and a voxel method's
// geometric error does), 10 % beyond and at least 1.5 times the miss, and measure there; once one resolution
// meets it and one below misses, fit error = c / r^p through the two and measure where it crosses the target
// (2 % beyond), until the two are within 5 % (or 2 voxels). An error that did not fall by 2 % since half the
// resolution (a floor, such as a faceted gem's refraction error) ends the search: not met, the resolution
// with the least error.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

namespace voxr {

struct ResolutionTrial {
  uint32_t resolution = 0;
  double error = 0.0;
};

struct ResolutionChoice {
  uint32_t resolution = 0;  // the smallest resolution measured to meet the target, else the least error's
  double error = 0.0;       // its measured error
  bool met = false;
  std::vector<ResolutionTrial> trials;  // in the order measured
};

// `measure(r)` returns the error at resolution r (any unit, the target's). Needs 2 <= lowest <= highest and a
// finite target >= 0; throws voxr::Error otherwise, and for a NaN measurement.
ResolutionChoice choose_resolution(double target, uint32_t lowest, uint32_t highest,
                                   const std::function<double(uint32_t)>& measure);

}  // namespace voxr
