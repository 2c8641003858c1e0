// The OpenCL runtime and an engine (Voxelizer, FrameRenderer) with every program a run needs built, made on
// a second thread while the input is read: what a fresh `voxr` process waits for least.
#pragma once

#include <future>
#include <memory>
#include <string>

#include "cl/cl_runtime.h"
#include "util/clock.h"

namespace voxr {

template <typename Engine>
struct PreparedRuntime {
  std::unique_ptr<ClRuntime> cl;
  std::unique_ptr<Engine> engine;
  double runtime_ms = 0.0;   // opening the device
  double programs_ms = 0.0;  // building or loading the programs
};

// Opens `device`, makes an Engine on it and calls engine.prepare(options), on another thread.
template <typename Engine, typename Options>
std::future<PreparedRuntime<Engine>> prepare_in_background(const std::string& device,
                                                           const Options& options) {
  return std::async(std::launch::async, [device, options] {
    const auto start = Clock::now();
    PreparedRuntime<Engine> p;
    p.cl = std::make_unique<ClRuntime>(device);
    p.runtime_ms = ms_since(start);
    p.engine = std::make_unique<Engine>(*p.cl);
    p.engine->prepare(options);
    p.programs_ms = p.cl->build_ms();
    return p;
  });
}

}  // namespace voxr
