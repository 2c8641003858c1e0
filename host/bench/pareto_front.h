// The Pareto front of speed against accuracy: the runs that no other run beats, for `voxr bench pareto`'s
// charts and its "pick for a target error" tables.
#pragma once

#include <vector>

namespace voxr {

struct ParetoPoint {
  double time = 0.0;   // any unit, lower is better
  double error = 0.0;  // any unit, lower is better
};

// One flag per point: true when no other point has time <= and error <= with one of the two strictly lower.
// Equal points are on the front together. A point with a NaN time or error is never on the front and beats
// none.
std::vector<bool> pareto_front(const std::vector<ParetoPoint>& points);

}  // namespace voxr
