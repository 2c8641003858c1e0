#include "cl/profiler.h"

#include <fmt/format.h>

#include <algorithm>

namespace voxr {

void Profiler::resolve() {
  for (Pending& p : pending_) {
    const cl_ulong start = p.event.getProfilingInfo<CL_PROFILING_COMMAND_START>();
    const cl_ulong end = p.event.getProfilingInfo<CL_PROFILING_COMMAND_END>();
    times_[p.name].push_back(double(end - start) * 1e-6);
  }
  pending_.clear();
}

void Profiler::clear() {
  pending_.clear();
  times_.clear();
}

std::map<std::string, Profiler::Stat> Profiler::stats() const {
  std::map<std::string, Stat> out;
  for (const auto& [name, ms] : times_) {
    Stat s;
    s.count = ms.size();
    for (double t : ms) s.total_ms += t;
    std::vector<double> sorted = ms;
    std::sort(sorted.begin(), sorted.end());
    const size_t n = sorted.size();
    s.median_ms = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
    out[name] = s;
  }
  return out;
}

Profiler::Split Profiler::since(const std::map<std::string, Stat>& before) const {
  Split split;
  for (const auto& [name, s] : stats()) {
    const auto it = before.find(name);
    const double ms = s.total_ms - (it == before.end() ? 0.0 : it->second.total_ms);
    if (!(ms > 0.0)) continue;
    if (name.rfind("upload", 0) == 0) {
      split.upload_ms += ms;
    } else if (name.rfind("readback", 0) == 0) {
      split.readback_ms += ms;
    } else {
      split.kernels_ms += ms;
      split.stage_ms[name] += ms;
    }
  }
  return split;
}

double Profiler::total_ms(const std::string& name) const {
  const auto it = times_.find(name);
  if (it == times_.end()) return 0.0;
  double sum = 0.0;
  for (double t : it->second) sum += t;
  return sum;
}

double Profiler::sum_ms() const {
  double sum = 0.0;
  for (const auto& [name, ms] : times_)
    for (double t : ms) sum += t;
  return sum;
}

std::string Profiler::table() const {
  std::vector<std::pair<std::string, Stat>> rows;
  for (const auto& row : stats()) rows.push_back(row);
  std::sort(rows.begin(), rows.end(),
            [](const auto& a, const auto& b) { return a.second.total_ms > b.second.total_ms; });
  std::string out = fmt::format("{:<24} {:>7} {:>11} {:>11}\n", "kernel", "count", "total ms", "median ms");
  for (const auto& [name, s] : rows)
    out += fmt::format("{:<24} {:>7} {:>11.3f} {:>11.3f}\n", name, s.count, s.total_ms, s.median_ms);
  return out;
}

}  // namespace voxr
