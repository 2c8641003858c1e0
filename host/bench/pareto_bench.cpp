#include "bench/pareto_bench.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "bench/bench_meshes.h"
#include "bench/pareto_front.h"
#include "bench/refraction_bench.h"
#include "bench/report_fields.h"
#include "bench/shadow_bench.h"
#include "metrics/voxel_surface_error.h"
#include "util/error.h"

namespace voxr {

namespace {

bool wants(const ParetoBenchOptions& options, const std::string& effect) {
  return std::find(options.effects.begin(), options.effects.end(), effect) != options.effects.end();
}

std::vector<ParetoRow> voxelization_rows(ClRuntime& cl, const ParetoBenchOptions& args) {
  Table1Options options;
  for (const std::string& mesh : args.vox_meshes) options.models.push_back({mesh, mesh});
  options.resolutions = args.vox_res;
  options.methods = args.vox_methods.empty() ? table1_methods() : args.vox_methods;
  options.peers = args.vox_peers;
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

ShadowBenchOptions shadow_options(const ParetoBenchOptions& args) {
  ShadowBenchOptions a;
  a.scenes = args.shadow_scenes;
  a.resolutions = args.shadow_res;
  if (!args.shadow_methods.empty()) a.methods = args.shadow_methods;
  a.size = args.size;
  a.repeat = args.repeat;
  a.warmup = args.warmup;
  return a;
}

std::vector<ParetoRow> shadow_rows(ClRuntime& cl, const ParetoBenchOptions& args) {
  std::vector<ParetoRow> rows;
  for (const ShadowBenchRow& r : measure_shadows(cl, shadow_options(args)).rows) {
    const bool reference = r.method == "reference";
    const std::string method = r.mode == "-" || reference ? r.method : r.method + "-" + r.mode;
    rows.push_back({"shadows", r.scene, method, r.resolution, r.frame_ms, r.frame_min, r.frame_max, "frame",
                    reference ? 0.0 : r.error.rmse, "transmittance_rmse", r.device_bytes, r.load, reference});
  }
  return rows;
}

RefractionBenchOptions refraction_options(const ParetoBenchOptions& args) {
  RefractionBenchOptions a;
  a.scenes = args.refraction_scenes;
  a.resolutions = args.refraction_res;
  if (!args.refraction_methods.empty()) a.methods = args.refraction_methods;
  a.size = args.size;
  a.repeat = args.repeat;
  a.warmup = args.warmup;
  return a;
}

std::vector<ParetoRow> refraction_rows(ClRuntime& cl, const ParetoBenchOptions& args) {
  std::vector<ParetoRow> rows;
  for (const RefractionBenchRow& r : measure_refraction(cl, refraction_options(args)).rows) {
    const bool reference = r.method == "reference-matched";
    // The papers' methods are named with their step rule and normals; the others have none.
    const bool voxel_march = r.method == "voxel-multi" || r.method == "voxel-two";
    const std::string method =
        voxel_march && !r.step.empty() ? fmt::format("{}-{}-{}", r.method, r.step, r.normals) : r.method;
    rows.push_back({"refraction", r.scene, method, r.resolution, r.frame_ms, r.frame_min, r.frame_max,
                    "frame", reference ? 0.0 : r.error.rmse, "image_rmse", r.grid_bytes, r.load, reference});
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

}  // namespace

const std::vector<std::string>& pareto_effects() {
  static const std::vector<std::string> effects = {"voxelization", "shadows", "refraction"};
  return effects;
}

void check_pareto_bench(const ParetoBenchOptions& options) {
  if (options.effects.empty()) fail("bench pareto: no effects (--effects)");
  for (const std::string& e : options.effects)
    if (std::find(pareto_effects().begin(), pareto_effects().end(), e) == pareto_effects().end())
      fail("bench pareto: unknown effect '{}' (effects: voxelization, shadows, refraction)", e);
  if (wants(options, "voxelization")) {
    std::vector<std::string> known = table1_methods();
    for (const auto& [name, peer] : options.vox_peers) known.push_back(name);
    for (const std::string& m : options.vox_methods)
      if (std::find(known.begin(), known.end(), m) == known.end())
        fail("bench pareto: --vox-methods: unknown method '{}' (known: {})", m, fmt::join(known, ", "));
    for (const std::string& mesh : options.vox_meshes) make_bench_mesh(mesh);
  }
  if (wants(options, "shadows"))
    for (const std::string& scene : options.shadow_scenes)
      if (scene != "default" && !std::filesystem::exists(scene))
        fail("bench pareto: --shadow-scenes: {}: no such file", scene);
  if (wants(options, "refraction")) check_refraction_bench(refraction_options(options));
}

std::vector<ParetoRow> measure_pareto(ClRuntime& cl, const ParetoBenchOptions& options) {
  std::vector<ParetoRow> rows;
  const auto append = [&rows](std::vector<ParetoRow> more) {
    rows.insert(rows.end(), more.begin(), more.end());
  };
  if (wants(options, "voxelization")) {
    fmt::print("voxelization\n");
    append(voxelization_rows(cl, options));
  }
  if (wants(options, "shadows")) {
    fmt::print("shadows\n");
    append(shadow_rows(cl, options));
  }
  if (wants(options, "refraction")) {
    fmt::print("refraction\n");
    append(refraction_rows(cl, options));
  }
  mark_fronts(rows);
  return rows;
}

}  // namespace voxr
