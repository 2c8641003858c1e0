// voxr bench animation: parses into BenchAnimationArgs, runs the animation benchmark
// (bench/animation_bench.h) with fresh `voxr render SCENE --frames N --size SIZE` processes (opening the
// device, the cached programs, reading the scene, N frames, the last image written; `fresh` times), then
// writes OUT.csv and OUT.md (with the date, the command and the load average).
#pragma once

#include <string>

#include "bench/animation_bench.h"

namespace voxr::cli {

struct BenchAnimationArgs {
  AnimationBenchOptions bench;  // bench.size from `size`
  std::string size = "640x480";
  std::string device;
  std::string out = "animation";
  int fresh = 1;
};

int run_bench_animation(const BenchAnimationArgs& args);

}  // namespace voxr::cli
