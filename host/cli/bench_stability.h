// voxr bench stability: the stability suite (host/stability/stability_suite.h), every case's full version
// with --full or the small one the tests run, written to a generated Markdown page (docs/stability.md) with
// its pictures (--family runs some families only). Exit status 1 when a row breaks its bound (the failing
// rows printed), else 0.
#pragma once

#include <string>
#include <vector>

namespace voxr::cli {

struct BenchStabilityArgs {
  bool full = false;
  std::vector<std::string> families;  // empty: every family
  std::string doc = "docs/stability.md";
  std::string pictures = "docs/images/stability";  // "" writes none
  std::string device;
};

int run_bench_stability(const BenchStabilityArgs& args);

}  // namespace voxr::cli
