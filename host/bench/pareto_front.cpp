#include "bench/pareto_front.h"

#include <cmath>

namespace voxr {

namespace {

bool valid(const ParetoPoint& p) {
  return !std::isnan(p.time) && !std::isnan(p.error);
}

}  // namespace

std::vector<bool> pareto_front(const std::vector<ParetoPoint>& points) {
  std::vector<bool> front(points.size(), false);
  for (size_t i = 0; i < points.size(); ++i) {
    const ParetoPoint& p = points[i];
    if (!valid(p)) continue;
    bool beaten = false;
    for (size_t j = 0; j < points.size() && !beaten; ++j) {
      const ParetoPoint& q = points[j];
      beaten = valid(q) && q.time <= p.time && q.error <= p.error && (q.time < p.time || q.error < p.error);
    }
    front[i] = !beaten;
  }
  return front;
}

}  // namespace voxr
