// voxr bench pareto: speed against accuracy for every effect in one run (bench/pareto_bench.h). Parses into
// BenchParetoArgs, loads the OpenVDB peer when this build has it, runs, writes PREFIX.csv, then
// bench/pareto_charts.py draws one PNG per effect and a Markdown page with "pick for a target error" tables:
// PREFIX.md with PREFIX-charts/, or the --doc page (e.g. docs/pareto.md) with its pictures in images/pareto/
// beside it.
#pragma once

#include <string>

#include "bench/pareto_bench.h"

namespace voxr::cli {

struct BenchParetoArgs {
  ParetoBenchOptions bench;  // bench.size from `size`; bench.vox_methods empty: every Table 1 method + the
                             // peers this build has
  std::string size = "320x240";
  std::string device;
  std::string out = "pareto";
  std::string doc;  // the Markdown page to write (pictures in images/pareto/ beside it); empty: PREFIX.md
};

// Runs the effects on one device, writes the CSV, the charts and the page. Throws voxr::Error for an unknown
// effect, method, mesh or scene.
int run_bench_pareto(const BenchParetoArgs& args);

}  // namespace voxr::cli
