// Per-kernel (and per-transfer) timings from OpenCL profiling events: count and total over the whole run,
// median over the last kWindow events of each name, so a process that runs frame after frame keeps a
// bounded amount of memory.
#pragma once

#include <CL/opencl.hpp>

#include <map>
#include <string>
#include <vector>

namespace voxr {

class Profiler {
 public:
  struct Stat {
    size_t count = 0;        // events ever recorded under the name
    double total_ms = 0.0;   // their summed time
    double median_ms = 0.0;  // median of the last kWindow
  };
  static constexpr size_t kWindow = 256;

  // Remembers an event; its time is read by resolve() once the queue has finished.
  void record(const std::string& name, const cl::Event& event) { pending_.push_back({name, event}); }
  void resolve();
  void clear();

  std::map<std::string, Stat> stats() const;

  // What was recorded since `before` (an earlier stats()), split by name: transfers named "upload..." and
  // "readback...", and everything else as kernel time per stage.
  struct Split {
    double upload_ms = 0.0;
    double readback_ms = 0.0;
    double kernels_ms = 0.0;
    std::map<std::string, double> stage_ms;
  };
  Split since(const std::map<std::string, Stat>& before) const;
  double total_ms(const std::string& name) const;  // 0 when never recorded
  size_t window(const std::string& name) const;    // times kept for the median (at most kWindow)
  double sum_ms() const;                           // every kernel and transfer
  // Aligned text table, one row per name, sorted by total time.
  std::string table() const;

 private:
  struct Pending {
    std::string name;
    cl::Event event;
  };
  struct Series {
    size_t count = 0;
    double total_ms = 0.0;
    std::vector<double> recent;  // ring buffer of the last kWindow times
  };
  std::vector<Pending> pending_;
  std::map<std::string, Series> times_;
};

}  // namespace voxr
