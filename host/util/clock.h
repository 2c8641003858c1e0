// The steady wall clock every phase time (ms fields, --timings, bench rows) is read from.
#pragma once

#include <chrono>

namespace voxr {

using Clock = std::chrono::steady_clock;

// Milliseconds since `start` on the steady clock.
inline double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace voxr
