// voxr bench pareto: speed against accuracy for every effect in one run. Voxelization (every Table 1 method,
// OpenVDB when its plugin is built), shadows (bench shadows' methods) and refraction (bench refraction's
// methods), each over its resolutions on a small fixed scene set, measured by the effect's own benchmark
// (bench/table1.h, cli/bench_shadows.h, cli/bench_refraction.h):
//   voxelization  time: warm kernel ms (profiling events); error: the two-sided mean surface distance
//                 between the voxels and the triangles relative to the scene size
//                 (metrics/voxel_surface_error.h, chamfer);
//   shadows       time: warm frame wall ms; error: transmittance RMSE at the visible receivers vs Embree;
//   refraction    time: warm frame wall ms; error: image RMSE vs the matched Embree reference (exact
//   shadows).
// The references themselves are not rows. Per (effect, scene) the Pareto front over every method and
// resolution is marked (bench/pareto_front.h). Writes PREFIX.csv, then bench/pareto_charts.py draws one PNG
// per effect and a Markdown page with "pick for a target error" tables: PREFIX.md with PREFIX-charts/, or
// the --doc page (e.g. docs/pareto.md) with its pictures in images/pareto/ beside it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace voxr::cli {

struct BenchParetoArgs {
  std::vector<std::string> effects = {"voxelization", "shadows", "refraction"};
  // Bench meshes (bench/bench_meshes.h): a smooth closed surface and thin features.
  std::vector<std::string> vox_meshes = {"bunny", "dragon"};
  std::vector<uint32_t> vox_res = {64, 128, 256, 512};
  std::vector<std::string> vox_methods;  // empty: every Table 1 method + the peers this build has
  std::vector<std::string> shadow_scenes = {"default", "data/scenes/foliage.json"};
  std::vector<uint32_t> shadow_res = {64, 128, 256, 512};
  std::vector<std::string> shadow_methods;  // empty: bench shadows' default methods
  std::vector<std::string> refraction_scenes = {"data/scenes/glass-sphere.json",
                                                "data/scenes/bunny-glass-130.json"};
  std::vector<uint32_t> refraction_res = {64, 128, 256, 512};
  std::vector<std::string> refraction_methods;  // empty: bench refraction's default methods
  std::string size = "320x240";                 // shadows' and refraction's images
  uint32_t surface_samples = 10000;             // voxel_surface_error's samples per case
  int repeat = 3;
  int warmup = 1;
  std::string device;
  std::string out = "pareto";
  std::string doc;  // the Markdown page to write (pictures in images/pareto/ beside it); empty: PREFIX.md
};

// Runs the effects on one device, writes the CSV, the charts and the page. Throws voxr::Error for an unknown
// effect, method, mesh or scene.
int run_bench_pareto(const BenchParetoArgs& args);

}  // namespace voxr::cli
