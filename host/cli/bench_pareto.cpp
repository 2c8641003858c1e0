#include "cli/bench_pareto.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "bench/bench_meshes.h"
#include "bench/pareto_front.h"
#include "bench/table1.h"
#include "cl/cl_runtime.h"
#include "cli/bench_refraction.h"
#include "cli/bench_shadows.h"
#include "cli/bench_support.h"
#include "cli/commands.h"
#include "cli/openvdb_plugin.h"
#include "cli/option_groups.h"
#include "cli/process.h"
#include "core/grid_spec.h"
#include "io/atomic_file.h"
#include "metrics/voxel_surface_error.h"
#include "util/error.h"

namespace voxr::cli {

namespace fs = std::filesystem;

namespace {

// Debian's python3, where python3-matplotlib is installed (a pyenv or venv python3 first on PATH may lack
// it).
constexpr const char* kSystemPython = "/usr/bin/python3";

const std::vector<std::string> kEffects = {"voxelization", "shadows", "refraction"};

// One CSV row: a method at a resolution on a scene, for one effect.
struct ParetoRow {
  std::string effect, scene, method;
  uint32_t resolution = 0;  // 0: the method has no resolution (image-space)
  double time_ms = 0, time_min = 0, time_max = 0;
  std::string time_measure;  // "kernels" or "frame"
  double error = 0;
  std::string error_measure;
  uint64_t bytes = 0;
  double load = 0;  // 1-minute load average when the case finished
  bool front = false;
};

bool wants(const BenchParetoArgs& args, const std::string& effect) {
  return std::find(args.effects.begin(), args.effects.end(), effect) != args.effects.end();
}

std::vector<ParetoRow> voxelization_rows(ClRuntime& cl, const BenchParetoArgs& args) {
  Table1Options options;
  for (const std::string& mesh : args.vox_meshes) options.models.push_back({mesh, mesh});
  options.resolutions = args.vox_res;
  options.methods = args.vox_methods.empty() ? table1_methods_with_peers() : args.vox_methods;
  add_table1_peers(options);
  options.repeat = args.repeat;
  options.warmup = args.warmup;
  options.accuracy = false;
  const uint32_t samples = args.surface_samples;
  options.surface_error = [samples](const VoxelGrid& grid, const GridSpec& spec, const TriangleSoup& soup) {
    return voxel_surface_error(grid, spec, soup, samples).chamfer();
  };
  std::vector<double> loads;
  options.progress = [&loads](const std::string& line) {
    loads.push_back(load_averages()[0]);
    fmt::print("  {}\n", line);
    std::fflush(stdout);
  };
  const std::vector<Table1Row> table = run_table1(cl, options);
  std::vector<ParetoRow> rows;
  for (size_t i = 0; i < table.size(); ++i) {
    const Table1Row& t = table[i];
    rows.push_back({"voxelization", t.mesh, t.method, t.res, t.kernels_ms, t.kernels_min_ms, t.kernels_max_ms,
                    "kernels", t.surface_error, "chamfer_rel", t.grid_bytes, loads[i]});
  }
  return rows;
}

std::vector<ParetoRow> shadow_rows(ClRuntime& cl, const BenchParetoArgs& args) {
  BenchShadowsArgs a;
  a.scenes = args.shadow_scenes;
  a.resolutions = args.shadow_res;
  if (!args.shadow_methods.empty()) a.methods = args.shadow_methods;
  a.size = args.size;
  a.repeat = args.repeat;
  a.warmup = args.warmup;
  a.fresh = 0;
  std::vector<ParetoRow> rows;
  for (const ShadowBenchRow& r : measure_shadows(cl, a).rows) {
    if (r.method == "reference") continue;
    const std::string method = r.mode == "-" ? r.method : r.method + "-" + r.mode;
    rows.push_back({"shadows", r.scene, method, r.resolution, r.frame_ms, r.frame_min, r.frame_max, "frame",
                    r.error.rmse, "transmittance_rmse", r.device_bytes, r.load});
  }
  return rows;
}

std::vector<ParetoRow> refraction_rows(ClRuntime& cl, const BenchParetoArgs& args) {
  BenchRefractionArgs a;
  a.scenes = args.refraction_scenes;
  a.resolutions = args.refraction_res;
  if (!args.refraction_methods.empty()) a.methods = args.refraction_methods;
  a.size = args.size;
  a.repeat = args.repeat;
  a.warmup = args.warmup;
  a.fresh = 0;
  std::vector<ParetoRow> rows;
  for (const RefractionBenchRow& r : measure_refraction(cl, a).rows) {
    if (r.method == "reference-matched") continue;
    const std::string method =
        r.step.empty() ? r.method : fmt::format("{}-{}-{}", r.method, r.step, r.normals);
    rows.push_back({"refraction", r.scene, method, r.resolution, r.frame_ms, r.frame_min, r.frame_max,
                    "frame", r.error.rmse, "image_rmse", r.grid_bytes, r.load});
  }
  return rows;
}

// Marks the Pareto front of each (effect, scene) over its methods and resolutions.
void mark_fronts(std::vector<ParetoRow>& rows) {
  std::vector<bool> done(rows.size(), false);
  for (size_t i = 0; i < rows.size(); ++i) {
    if (done[i]) continue;
    std::vector<size_t> group;
    std::vector<ParetoPoint> points;
    for (size_t j = i; j < rows.size(); ++j)
      if (rows[j].effect == rows[i].effect && rows[j].scene == rows[i].scene) {
        group.push_back(j);
        points.push_back({rows[j].time_ms, rows[j].error});
        done[j] = true;
      }
    const std::vector<bool> front = pareto_front(points);
    for (size_t k = 0; k < group.size(); ++k) rows[group[k]].front = front[k];
  }
}

std::string number(double v, int digits) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format("{:.{}g}", v, digits);
}

std::string csv_text(const std::vector<ParetoRow>& rows) {
  std::ostringstream csv;
  csv << "effect,scene,method,resolution,time_ms,time_ms_min,time_ms_max,time_measure,error,error_measure,"
         "bytes,load_1min,front\n";
  for (const ParetoRow& r : rows)
    csv << fmt::format("{},{},{},{},{:.4f},{:.4f},{:.4f},{},{},{},{},{:.2f},{}\n", r.effect, r.scene,
                       r.method, r.resolution ? std::to_string(r.resolution) : "", r.time_ms, r.time_min,
                       r.time_max, r.time_measure, number(r.error, 6), r.error_measure, r.bytes, r.load,
                       r.front ? 1 : 0);
  return csv.str();
}

}  // namespace

int run_bench_pareto(const BenchParetoArgs& args) {
  if (args.effects.empty()) fail("bench pareto: no effects (--effects)");
  for (const std::string& e : args.effects)
    if (std::find(kEffects.begin(), kEffects.end(), e) == kEffects.end())
      fail("bench pareto: unknown effect '{}' (effects: voxelization, shadows, refraction)", e);
  // Everything an effect would refuse is refused before any effect runs (a late error would lose minutes of
  // measurements and write nothing).
  if (wants(args, "voxelization")) {
    const std::vector<std::string> known = table1_methods_with_peers();
    for (const std::string& m : args.vox_methods)
      if (std::find(known.begin(), known.end(), m) == known.end())
        fail("bench pareto: --vox-methods: unknown method '{}' (known: {})", m, fmt::join(known, ", "));
    for (const std::string& mesh : args.vox_meshes) make_bench_mesh(mesh);
  }
  if (wants(args, "shadows"))
    for (const std::string& scene : args.shadow_scenes)
      if (scene != "default" && !fs::exists(scene))
        fail("bench pareto: --shadow-scenes: {}: no such file", scene);
  if (wants(args, "refraction")) {
    BenchRefractionArgs a;
    a.scenes = args.refraction_scenes;
    if (!args.refraction_methods.empty()) a.methods = args.refraction_methods;
    a.size = args.size;
    check_bench_refraction_args(a);
  }
  const fs::path out_dir = fs::path(args.out).parent_path();
  if (!out_dir.empty() && !fs::is_directory(out_dir))
    fail("--out {}: folder '{}' does not exist", args.out, out_dir.string());
  const std::string load_before = load_average_text();
  ClRuntime cl(args.device);
  const std::string device = fmt::format("{} ({}, driver {})", cl.device().name, cl.device().platform_name,
                                         cl.device().driver_version);
  const std::string started = utc_now();
  fmt::print("device: {}\n", device);
  std::vector<ParetoRow> rows;
  const auto append = [&rows](std::vector<ParetoRow> more) {
    rows.insert(rows.end(), more.begin(), more.end());
  };
  if (wants(args, "voxelization")) {
    fmt::print("voxelization\n");
    append(voxelization_rows(cl, args));
  }
  if (wants(args, "shadows")) {
    fmt::print("shadows\n");
    append(shadow_rows(cl, args));
  }
  if (wants(args, "refraction")) {
    fmt::print("refraction\n");
    append(refraction_rows(cl, args));
  }
  mark_fronts(rows);
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
  sub->add_option("--effects", a->effects, "voxelization, shadows, refraction")
      ->delimiter(',')
      ->capture_default_str();
  CLI::Option* vox_meshes = sub->add_option("--vox-meshes", a->vox_meshes, "voxelization: bench meshes")
                                ->delimiter(',')
                                ->capture_default_str();
  CLI::Option* vox_res = add_grid_option(*sub, "--vox-res", GridKind::kVoxel, a->vox_res);
  sub->add_option("--vox-methods", a->vox_methods,
                  "voxelization: Table 1 methods (default: all, openvdb if built)")
      ->delimiter(',');
  sub->add_option("--vox-samples", a->surface_samples, "voxelization: surface error samples per case")
      ->check(CLI::Range(100u, 10000000u))
      ->capture_default_str();
  CLI::Option* shadow_scenes =
      sub->add_option("--shadow-scenes", a->shadow_scenes, "shadows: scene files or default")
          ->delimiter(',')
          ->capture_default_str();
  CLI::Option* shadow_res = add_grid_option(*sub, "--shadow-res", GridKind::kShadow, a->shadow_res);
  sub->add_option("--shadow-methods", a->shadow_methods, "shadows: methods (default: bench shadows')")
      ->delimiter(',');
  CLI::Option* refraction_scenes =
      sub->add_option("--refraction-scenes", a->refraction_scenes, "refraction: scene files")
          ->delimiter(',')
          ->capture_default_str();
  CLI::Option* refraction_res =
      add_grid_option(*sub, "--refraction-res", GridKind::kRefraction, a->refraction_res);
  sub->add_option("--refraction-methods", a->refraction_methods,
                  "refraction: methods (default: bench refraction's)")
      ->delimiter(',');
  add_size_option(*sub, a->size)->capture_default_str();
  add_repeat_options(*sub, a->repeat, a->warmup);
  return {sub, [=] {
            BenchParetoArgs args = *a;
            if (*quick) {
              // One scene per effect, two resolutions, where the options did not say otherwise.
              if (!vox_meshes->count()) args.vox_meshes = {"dragon"};
              if (!vox_res->count()) args.vox_res = {64, 256};
              if (!shadow_scenes->count()) args.shadow_scenes = {"default"};
              if (!shadow_res->count()) args.shadow_res = {64, 256};
              if (!refraction_scenes->count()) args.refraction_scenes = {"data/scenes/glass-sphere.json"};
              if (!refraction_res->count()) args.refraction_res = {64, 128};
            }
            return run_bench_pareto(args);
          }};
}

}  // namespace voxr::cli
