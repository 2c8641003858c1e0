// voxr bench shadows: parses into BenchShadowsArgs, runs the shadow benchmark (bench/shadow_bench.h) with
// fresh `voxr render SCENE --shadows voxel --shadow-res 256` processes (`fresh` times), then writes OUT.csv
// and OUT.md, then the charts (bench/shadow_charts.py) into OUT-charts/ when python3 and matplotlib are
// there.
#pragma once

#include <string>

#include "bench/shadow_bench.h"

namespace voxr::cli {

struct BenchShadowsArgs {
  ShadowBenchOptions bench;  // bench.size from `size`
  std::string size = "640x480";
  std::string device;
  std::string out = "shadows";
  int fresh = 3;
};

// measure_shadows, then OUT.csv, OUT.md and the charts.
int run_bench_shadows(const BenchShadowsArgs& args);

}  // namespace voxr::cli
