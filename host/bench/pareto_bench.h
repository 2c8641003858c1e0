// The speed/accuracy benchmark (`voxr bench pareto`): every effect's methods over their resolutions on a
// small fixed scene set, each measured by the effect's own benchmark (bench/table1.h, bench/shadow_bench.h,
// bench/refraction_bench.h):
//   voxelization  time: warm kernel ms (profiling events); error: the two-sided mean surface distance
//                 between the voxels and the triangles relative to the scene size
//                 (metrics/voxel_surface_error.h, chamfer);
//   shadows       time: warm frame wall ms; error: transmittance RMSE at the visible receivers vs Embree;
//   refraction    time: warm frame wall ms; error: image RMSE vs the matched Embree reference (exact
//                 shadows).
// The exact references are rows too (`reference` set, error 0 by definition, their frame time as the
// effect's benchmark measures it): a method slower than its reference is dominated by it. Per (effect,
// scene) the Pareto front over every method, resolution and the reference is marked
// (bench/pareto_front.h). Voxelization has no reference row (its exact CPU reference is not a contender).
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "bench/table1.h"
#include "cl/cl_runtime.h"

namespace voxr {

struct ParetoBenchOptions {
  std::vector<std::string> effects = {"voxelization", "shadows", "refraction"};
  // Bench meshes (bench/bench_meshes.h): a smooth closed surface and thin features.
  std::vector<std::string> vox_meshes = {"bunny", "dragon"};
  std::vector<uint32_t> vox_res = {64, 128, 256, 512};
  std::vector<std::string> vox_methods;         // Table 1 methods or vox_peers (empty: table1_methods())
  std::map<std::string, Table1Peer> vox_peers;  // e.g. OpenVDB (the CLI loads its plugin)
  std::vector<std::string> shadow_scenes = {"default", "data/scenes/foliage.json"};
  std::vector<uint32_t> shadow_res = {64, 128, 256, 512};
  std::vector<std::string> shadow_methods;  // empty: the shadow benchmark's default methods
  std::vector<std::string> refraction_scenes = {"data/scenes/glass-sphere.json",
                                                "data/scenes/bunny-glass-130.json",
                                                "data/scenes/thin-vase-floor.json"};
  std::vector<uint32_t> refraction_res = {64, 128, 256, 512};
  std::vector<std::string> refraction_methods;  // empty: the refraction benchmark's default methods
  glm::uvec2 size{320, 240};                    // shadows' and refraction's images
  uint32_t surface_samples = 10000;             // voxel_surface_error's samples per case
  int repeat = 3;
  int warmup = 1;
};

// One row: a method at a resolution on a scene, for one effect.
struct ParetoRow {
  std::string effect, scene, method;
  uint32_t resolution = 0;  // 0: the method has no resolution (image-space)
  double time_ms = 0, time_min = 0, time_max = 0;
  std::string time_measure;  // "kernels" or "frame"
  double error = 0;
  std::string error_measure;
  uint64_t bytes = 0;
  double load = 0;         // 1-minute load average when the case finished
  bool reference = false;  // the effect's exact reference (error 0)
  bool front = false;
};

// The effects' names, in the order they run.
const std::vector<std::string>& pareto_effects();

// Throws voxr::Error for an unknown effect, voxelization method or bench mesh, a missing shadow scene, or
// what check_refraction_bench refuses (everything an effect would refuse, before any effect runs: a late
// error would lose minutes of measurements); touches no device.
void check_pareto_bench(const ParetoBenchOptions& options);

// Runs the effects options.effects names on `cl`'s device, printing one line per case, and marks each
// (effect, scene)'s Pareto front.
std::vector<ParetoRow> measure_pareto(ClRuntime& cl, const ParetoBenchOptions& options);

}  // namespace voxr
