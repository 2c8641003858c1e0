// voxr bench: voxelize (fresh process, job and frame figures: cli/bench_voxelize.h), table1 (the papers'
// Table 1, every method), solid (the solid fill modes); shadows, refraction, stability, animation and pareto
// (cli/bench_shadows.h, cli/bench_refraction.h, cli/bench_stability.h, cli/bench_animation.h,
// cli/bench_pareto.h) live in voxr-render.
#include <fmt/format.h>

#include <algorithm>
#include <sstream>

#include "bench/bench_meshes.h"
#include "bench/solid_table.h"
#include "bench/table1.h"
#include "bench/voxelize_cases.h"
#include "cl/cl_runtime.h"
#include "cli/bench_voxelize.h"
#include "cli/commands.h"
#include "cli/openvdb_plugin.h"
#include "cli/option_groups.h"
#include "io/atomic_file.h"
#include "util/median.h"

namespace voxr::cli {

namespace {

void print_line(const std::string& line) {
  fmt::print("{}\n", line);
  std::fflush(stdout);
}

std::string device_description(const ClRuntime& cl) {
  return fmt::format("{} ({}, driver {})", cl.device().name, cl.device().platform_name,
                     cl.device().driver_version);
}

// Writes PREFIX + each extension's text and says so.
void write_report(const std::string& prefix, const std::vector<std::pair<std::string, std::string>>& files) {
  for (const auto& [ext, text] : files) {
    write_file_atomically(prefix + ext, text);
    fmt::print("wrote {}{}\n", prefix, ext);
  }
}

struct Table1Args {
  std::vector<std::string> models;  // LABEL=MESH or MESH; empty: the papers' six sizes
  std::vector<uint32_t> resolutions = {128, 256, 512};
  std::vector<std::string> methods = table1_methods_with_peers();
  std::string device;
  std::string out = "table1";
  int repeat = 3;
  int warmup = 1;
  bool no_accuracy = false;
};

int run_bench_table1(const Table1Args& args) {
  ClRuntime cl(args.device);
  Table1Options options;
  options.models = table1_default_models();
  if (!args.models.empty()) {
    options.models.clear();
    for (const std::string& m : args.models) {
      const size_t eq = m.find('=');
      options.models.push_back(eq == std::string::npos ? Table1Model{m, m}
                                                       : Table1Model{m.substr(0, eq), m.substr(eq + 1)});
    }
  }
  options.resolutions = args.resolutions;
  options.methods = args.methods;
  add_table1_peers(options);
  options.repeat = args.repeat;
  options.warmup = args.warmup;
  options.accuracy = !args.no_accuracy;
  options.progress = print_line;
  const std::string device = device_description(cl);
  fmt::print("device: {}\n", device);
  const std::vector<Table1Row> rows = run_table1(cl, options);
  write_report(args.out, {{".csv", table1_csv(rows, device)}, {".md", table1_markdown(rows, device)}});
  return 0;
}

struct SolidArgs {
  SolidTableOptions options;
  std::string device;
  std::string out = "solid";
};

int run_bench_solid(const SolidArgs& args) {
  ClRuntime cl(args.device);
  SolidTableOptions options = args.options;
  options.progress = print_line;
  const std::string device = device_description(cl);
  fmt::print("device: {}\n", device);
  const std::vector<SolidTableRow> rows = run_solid_table(cl, options);
  write_report(args.out,
               {{".csv", solid_table_csv(rows, device)}, {".md", solid_table_markdown(rows, device)}});
  return 0;
}

}  // namespace

Command add_bench(CLI::App& app) {
  CLI::App* sub =
      app.add_subcommand("bench", "Benchmarks (medians of repeated runs, profiled on the device)");
  sub->require_subcommand(1);
  auto args = std::make_shared<BenchVoxelizeArgs>();
  CLI::App* vox = sub->add_subcommand(
      "voxelize",
      "Fresh-process, in-process job and per-frame times over meshes x cases x resolutions -> CSV");
  vox->add_option("--meshes", args->meshes,
                  "benchmark meshes (torus, bunny, armadillo, ...; BASExN subdivides)")
      ->delimiter(',')
      ->capture_default_str();
  add_grid_option(*vox, "--res", GridKind::kVoxel, args->resolutions);
  std::string cases;
  for (const VoxelizeCase& c : voxelize_cases()) cases += (cases.empty() ? "" : ", ") + c.name;
  vox->add_option("--cases", args->cases, "cases: " + cases)->delimiter(',')->capture_default_str();
  add_device_option(*vox, args->device);
  vox->add_option("--out", args->out, "CSV file");
  vox->add_option("--write", args->write, "fresh processes also write -o out.EXT (e.g. binvox)");
  add_repeat_options(*vox, args->repeat, args->warmup);
  add_fresh_option(*vox, args->fresh, "voxr voxelize MESH --res R");
  auto table = std::make_shared<Table1Args>();
  CLI::App* t1 = sub->add_subcommand(
      "table1", "The papers' Table 1: every method x model x resolution, time and accuracy");
  t1->add_option("--models", table->models, "LABEL=MESH or MESH (default: the papers' six triangle counts)")
      ->delimiter(',');
  add_grid_option(*t1, "--res", GridKind::kVoxel, table->resolutions);
  t1->add_option("--methods", table->methods, "methods")->delimiter(',')->capture_default_str();
  add_device_option(*t1, table->device);
  add_out_prefix_option(*t1, table->out, "PREFIX.csv and PREFIX.md");
  add_repeat_options(*t1, table->repeat, table->warmup);
  t1->add_flag("--no-accuracy", table->no_accuracy, "skip the accuracy measures (time only)");
  auto solid = std::make_shared<SolidArgs>();
  CLI::App* so = sub->add_subcommand(
      "solid", "Solid modes x meshes (closed and with holes): time, missing/extra voxels");
  so->add_option("--meshes", solid->options.meshes, "bench meshes")->delimiter(',')->capture_default_str();
  add_grid_option(*so, "--res", GridKind::kVoxel, solid->options.resolutions);
  add_device_option(*so, solid->device);
  add_out_prefix_option(*so, solid->out, "PREFIX.csv and PREFIX.md");
  add_repeat_option(*so, solid->options.repeat);
  const Command shadows = add_bench_shadows(*sub);
  const Command refraction = add_bench_refraction(*sub);
  const Command stability = add_bench_stability(*sub);
  const Command animation = add_bench_animation(*sub);
  const Command pareto = add_bench_pareto(*sub);
  return {sub, [args, vox, table, t1, solid, so, shadows, refraction, stability, animation, pareto] {
            if (shadows.app->parsed()) return shadows.run();
            if (refraction.app->parsed()) return refraction.run();
            if (stability.app->parsed()) return stability.run();
            if (animation.app->parsed()) return animation.run();
            if (pareto.app->parsed()) return pareto.run();
            if (vox->parsed()) return run_bench_voxelize(*args);
            if (t1->parsed()) return run_bench_table1(*table);
            if (so->parsed()) return run_bench_solid(*solid);
            return 2;
          }};
}

}  // namespace voxr::cli
