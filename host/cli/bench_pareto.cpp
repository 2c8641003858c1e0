#include "cli/bench_pareto.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "bench/report_fields.h"
#include "cl/cl_runtime.h"
#include "cli/bench_support.h"
#include "cli/commands.h"
#include "cli/openvdb_plugin.h"
#include "cli/option_groups.h"
#include "cli/parse_args.h"
#include "cli/process.h"
#include "io/atomic_file.h"
#include "util/error.h"

namespace voxr::cli {

namespace fs = std::filesystem;

namespace {

// Debian's python3, where python3-matplotlib is installed (a pyenv or venv python3 first on PATH may lack
// it).
constexpr const char* kSystemPython = "/usr/bin/python3";

std::string number(double v, int digits) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format("{:.{}g}", v, digits);
}

std::string csv_text(const std::vector<ParetoRow>& rows) {
  std::ostringstream csv;
  csv << "effect,scene,method,resolution,time_ms,time_ms_min,time_ms_max,time_measure,error,error_measure,"
         "bytes,load_1min,reference,front\n";
  for (const ParetoRow& r : rows)
    csv << fmt::format("{},{},{},{},{:.4f},{:.4f},{:.4f},{},{},{},{},{:.2f},{},{}\n", r.effect, r.scene,
                       r.method, r.resolution ? std::to_string(r.resolution) : "", r.time_ms, r.time_min,
                       r.time_max, r.time_measure, number(r.error, 6), r.error_measure, r.bytes, r.load,
                       r.reference ? 1 : 0, r.front ? 1 : 0);
  return csv.str();
}

}  // namespace

int run_bench_pareto(const BenchParetoArgs& args) {
  ParetoBenchOptions options = args.bench;
  options.size = parse_size(args.size, "--size");
  if (std::find(options.effects.begin(), options.effects.end(), "voxelization") != options.effects.end()) {
    if (options.vox_methods.empty()) options.vox_methods = table1_methods_with_peers();
    if (openvdb_peer_available()) {
      Table1Options peers;
      peers.methods = options.vox_methods;
      add_table1_peers(peers);
      options.vox_peers = std::move(peers.peers);
    }
  }
  check_pareto_bench(options);
  const fs::path out_dir = fs::path(args.out).parent_path();
  if (!out_dir.empty() && !fs::is_directory(out_dir))
    fail("--out {}: folder '{}' does not exist", args.out, out_dir.string());
  const std::string load_before = load_average_text();
  ClRuntime cl(args.device);
  const std::string device = fmt::format("{} ({}, driver {})", cl.device().name, cl.device().platform_name,
                                         cl.device().driver_version);
  const std::string started = utc_now();
  fmt::print("device: {}\n", device);
  const std::vector<ParetoRow> rows = measure_pareto(cl, options);
  const std::string load_after = load_average_text();
  write_file_atomically(args.out + ".csv", csv_text(rows));
  fmt::print("wrote {}.csv\n", args.out);
  std::fflush(stdout);

  const fs::path page = args.doc.empty() ? fs::path(args.out + ".md") : fs::path(args.doc);
  const fs::path images =
      args.doc.empty() ? fs::path(args.out + "-charts") : page.parent_path() / "images" / "pareto";
  const fs::path script = fs::path(VOXR_SOURCE_DIR) / "bench" / "pareto_charts.py";
  const int status = run_program({kSystemPython, script.string(), args.out + ".csv", page.string(),
                                  images.string(), "--command", command_line(), "--device", device, "--date",
                                  started, "--load", load_before + " before, " + load_after + " after"});
  if (status != 0) {
    if (!args.doc.empty()) fail("{}: the page was not written ({} failed)", args.doc, script.string());
    fmt::print(stderr, "voxr: warning: the charts were not drawn ({} failed)\n", script.string());
  }
  return 0;
}

Command add_bench_pareto(CLI::App& bench) {
  auto a = std::make_shared<BenchParetoArgs>();
  auto quick = std::make_shared<bool>(false);
  CLI::App* sub = bench.add_subcommand(
      "pareto",
      "Speed against accuracy: every voxelization, shadow and refraction method x resolution, the "
      "Pareto fronts, charts and a page");
  add_out_prefix_option(*sub, a->out, "PREFIX.csv (and PREFIX.md, PREFIX-charts/ without --doc)");
  sub->add_option("--doc", a->doc,
                  "write this Markdown page (e.g. docs/pareto.md), pictures in images/pareto/ "
                  "beside it");
  sub->add_flag("--quick", *quick, "one scene per effect, two resolutions (options given win)");
  add_device_option(*sub, a->device);
  sub->add_option("--effects", a->bench.effects, "voxelization, shadows, refraction")
      ->delimiter(',')
      ->capture_default_str();
  CLI::Option* vox_meshes = sub->add_option("--vox-meshes", a->bench.vox_meshes, "voxelization: bench meshes")
                                ->delimiter(',')
                                ->capture_default_str();
  CLI::Option* vox_res = add_grid_option(*sub, "--vox-res", GridKind::kVoxel, a->bench.vox_res);
  sub->add_option("--vox-methods", a->bench.vox_methods,
                  "voxelization: Table 1 methods (default: all, openvdb if built)")
      ->delimiter(',');
  sub->add_option("--vox-samples", a->bench.surface_samples, "voxelization: surface error samples per case")
      ->check(CLI::Range(100u, 10000000u))
      ->capture_default_str();
  CLI::Option* shadow_scenes =
      sub->add_option("--shadow-scenes", a->bench.shadow_scenes, "shadows: scene files or default")
          ->delimiter(',')
          ->capture_default_str();
  CLI::Option* shadow_res = add_grid_option(*sub, "--shadow-res", GridKind::kShadow, a->bench.shadow_res);
  sub->add_option("--shadow-methods", a->bench.shadow_methods, "shadows: methods (default: bench shadows')")
      ->delimiter(',');
  CLI::Option* refraction_scenes =
      sub->add_option("--refraction-scenes", a->bench.refraction_scenes, "refraction: scene files")
          ->delimiter(',')
          ->capture_default_str();
  CLI::Option* refraction_res =
      add_grid_option(*sub, "--refraction-res", GridKind::kRefraction, a->bench.refraction_res);
  sub->add_option("--refraction-methods", a->bench.refraction_methods,
                  "refraction: methods (default: bench refraction's)")
      ->delimiter(',');
  add_size_option(*sub, a->size)->capture_default_str();
  add_repeat_options(*sub, a->bench.repeat, a->bench.warmup);
  return {sub, [=] {
            BenchParetoArgs args = *a;
            if (*quick) {
              // One scene per effect, two resolutions, where the options did not say otherwise.
              if (!vox_meshes->count()) args.bench.vox_meshes = {"dragon"};
              if (!vox_res->count()) args.bench.vox_res = {64, 256};
              if (!shadow_scenes->count()) args.bench.shadow_scenes = {"default"};
              if (!shadow_res->count()) args.bench.shadow_res = {64, 256};
              if (!refraction_scenes->count())
                args.bench.refraction_scenes = {"data/scenes/glass-sphere.json"};
              if (!refraction_res->count()) args.bench.refraction_res = {64, 128};
            }
            return run_bench_pareto(args);
          }};
}

}  // namespace voxr::cli
