// voxr bench refraction: parses into BenchRefractionArgs, runs the refraction benchmark
// (bench/refraction_bench.h) with fresh `voxr render SCENE --refraction voxel-multi --res 256` processes
// (same shadows and size, `fresh` times), then writes OUT.csv and OUT.md, then the charts
// (bench/shadow_charts.py: time against rmse and against angle_mean_deg) into OUT-charts/rmse/ and
// OUT-charts/angle_mean_deg/ when python3 and matplotlib are there.
#pragma once

#include <string>

#include "bench/refraction_bench.h"

namespace voxr::cli {

struct BenchRefractionArgs {
  RefractionBenchOptions bench;  // bench.size from `size`
  std::string size = "640x480";
  std::string device;
  std::string out = "refraction";
  int fresh = 3;
};

// measure_refraction, then OUT.csv, OUT.md and the charts.
int run_bench_refraction(const BenchRefractionArgs& args);

}  // namespace voxr::cli
