#include "core/resolution_search.h"

#include <algorithm>
#include <cmath>

#include "util/error.h"

namespace voxr {

ResolutionChoice choose_resolution(double target, uint32_t lowest, uint32_t highest,
                                   const std::function<double(uint32_t)>& measure) {
  if (!(std::isfinite(target) && target >= 0.0)) fail("error target {} is not a finite number >= 0", target);
  if (lowest < 2 || lowest > highest) fail("resolution search: bad range {}..{}", lowest, highest);
  ResolutionChoice choice;
  const auto trial = [&](uint32_t r) {
    const double e = measure(r);
    if (std::isnan(e)) fail("resolution search: the error at resolution {} is not a number", r);
    choice.trials.push_back({r, e});
    return e;
  };
  uint32_t bad = 0, good = 0;  // the largest missing and the smallest meeting resolution measured
  double bad_error = 0.0, good_error = 0.0;
  const auto record = [&](uint32_t r, double e) {
    if (e <= target) {
      if (!good || r < good) good = r, good_error = e;
    } else if (r > bad) {
      bad = r, bad_error = e;
    }
  };
  const auto floor_below = [&](uint32_t r, double e) {
    for (auto t = choice.trials.rbegin(); t != choice.trials.rend(); ++t)
      if (2 * t->resolution <= r) return e >= 0.98 * t->error;
    return false;
  };
  record(lowest, trial(lowest));
  while (!good && bad < highest) {
    // Error ~ c / r: the resolution where c / r = target, 10 % beyond, at least 50 % above the last miss.
    const double predicted = bad_error > 0.0 && target > 0.0 ? 1.1 * bad * bad_error / target : highest;
    const uint32_t r =
        uint32_t(std::clamp(std::ceil(std::max(predicted, 1.5 * bad)), double(bad + 1), double(highest)));
    const double e = trial(r);
    record(r, e);
    // A floor: the error did not fall by 2 % since half this resolution; more voxels will not help.
    if (e > target && floor_below(r, e)) break;
  }
  if (!good) {
    // Not met: the least error measured (the smallest resolution among equals).
    const ResolutionTrial best = *std::min_element(
        choice.trials.begin(), choice.trials.end(), [](const ResolutionTrial& a, const ResolutionTrial& b) {
          return a.error < b.error || (a.error == b.error && a.resolution < b.resolution);
        });
    choice.resolution = best.resolution;
    choice.error = best.error;
    return choice;
  }
  // Between a miss and a hit: error ~ c / r^p through both (log-log secant), the guess kept inside.
  while (bad && good > bad + std::max(2u, good / 20)) {  // bad == 0: met at the lowest
    double guess = bad + 0.5 * (good - bad);
    if (bad_error > target && good_error > 0.0 && bad_error > good_error) {
      const double p = std::log(bad_error / good_error) / std::log(double(good) / bad);
      guess = 1.02 * bad * std::pow(bad_error / target, 1.0 / p);
    }
    // At least the stopping gap below the hit, so that each measurement ends the search or narrows it.
    const double below_good = double(good) - std::max(2u, good / 20);
    const uint32_t r = uint32_t(std::clamp(std::round(guess), double(bad + 1), below_good));
    record(r, trial(r));
  }
  choice.resolution = good;
  choice.error = good_error;
  choice.met = true;
  return choice;
}

}  // namespace voxr
