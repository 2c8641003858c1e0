// voxr bench stability: the stability suite (host/stability/stability_suite.h), every case's full version
// with --full or the small one the tests run, written to a generated Markdown page (docs/stability.md) with
// its pictures. Exit status 1 when a row breaks its bound (the failing rows printed), else 0.
#pragma once

#include <string>

namespace voxr::cli {

struct BenchStabilityArgs {
  bool full = false;
  std::string doc = "docs/stability.md";
  std::string pictures = "docs/images/stability";  // "" writes none
  std::string device;
};

int run_bench_stability(const BenchStabilityArgs& args);

}  // namespace voxr::cli
