#include "cl/profiler.h"

#include <fmt/format.h>

#include <algorithm>

namespace voxr {

void Profiler::resolve() {
  for (Pending& p : pending_) {
    const cl_ulong start = p.event.getProfilingInfo<CL_PROFILING_COMMAND_START>();
    const cl_ulong end = p.event.getProfilingInfo<CL_PROFILING_COMMAND_END>();
    Series& series = times_[p.name];
    const double ms = double(end - start) * 1e-6;
    if (series.recent.size() < kWindow)
      series.recent.push_back(ms);
    else
      series.recent[series.count % kWindow] = ms;
    ++series.count;
    series.total_ms += ms;
  }
  pending_.clear();
}

void Profiler::clear() {
  pending_.clear();
  times_.clear();
}

std::map<std::string, Profiler::Stat> Profiler::stats() const {
  std::map<std::string, Stat> out;
  for (const auto& [name, series] : times_) {
    Stat s;
    s.count = series.count;
    s.total_ms = series.total_ms;
    std::vector<double> sorted = series.recent;
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
  return it == times_.end() ? 0.0 : it->second.total_ms;
}

size_t Profiler::window(const std::string& name) const {
  const auto it = times_.find(name);
  return it == times_.end() ? 0 : it->second.recent.size();
}

double Profiler::sum_ms() const {
  double sum = 0.0;
  for (const auto& [name, series] : times_) sum += series.total_ms;
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
