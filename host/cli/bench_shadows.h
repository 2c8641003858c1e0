// voxr bench shadows: every shadow method x shadow resolution x scene, time against error, in one run.
// Per scene, the camera's samples are the same for every method (one kernel rasterizer), so the exact
// transmittance at them is traced once with Embree and every method is measured against it:
//   frame    warm per-frame wall time of FrameRenderer::render (light grid fit, voxelize from the light or
//            rasterize the light maps, accumulate, camera raster + resolve, lookup, shade, image read back),
//            median with min and max of `repeat` frames after `warmup`;
//   error    transmittance RMSE and maximum over the visible receivers, share of receivers off by > 0.05,
//            PSNR of the shaded image against the same samples shaded with the exact transmittance;
//   reference  Embree's frame for a deforming scene: BVH rebuild + the same shadow rays (+ shading), as
//            measured here on the host's cores;
//   fresh    `voxr render SCENE --shadows voxel --shadow-res 256` as a new process, `fresh` times.
// Writes OUT.csv and OUT.md, then the charts (bench/shadow_charts.py) into OUT-charts/ when python3 and
// matplotlib are there.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cl/cl_runtime.h"
#include "metrics/image_metrics.h"

namespace voxr::cli {

struct BenchShadowsArgs {
  std::vector<std::string> scenes = {"default", "data/scenes/shadow-tree.json", "data/scenes/foliage.json",
                                     "data/scenes/glass-floor.json"};
  std::vector<uint32_t> resolutions = {64, 128, 256, 512};
  std::vector<std::string> methods = {"voxel-center", "voxel-conservative", "uniform", "filter", "opaque"};
  std::string size = "640x480";
  std::string device;
  std::string out = "shadows";
  int repeat = 5;
  int warmup = 1;
  int fresh = 3;
};

// One measured case: a method at a shadow resolution on a scene, or the scene's Embree reference (method
// "reference", resolution 0).
struct ShadowBenchRow {
  std::string scene, method, mode;  // mode: the raster mode of the voxel method, else "-"
  uint32_t resolution = 0;
  double frame_ms = 0, frame_min = 0, frame_max = 0;  // warm frame wall ms: median, min, max
  TransmittanceError error{};                         // at the visible receivers against Embree
  double psnr = 0;                                    // dB, of the image against the exact transmittance
  std::string light_grid;
  uint64_t device_bytes = 0;
  uint64_t triangles = 0;
  double load = 0;  // 1-minute load average when the case finished
};

struct ShadowBenchRun {
  std::vector<ShadowBenchRow> rows;  // per scene: the reference, then methods x resolutions
  std::string fresh_table;           // Markdown rows of the fresh processes (empty when args.fresh is 0)
};

// Runs the measurements on `cl`'s device, printing one line per case. args.out is not used. Throws
// voxr::Error for an unknown method or an unreadable scene.
ShadowBenchRun measure_shadows(ClRuntime& cl, const BenchShadowsArgs& args);

// measure_shadows, then OUT.csv, OUT.md and the charts.
int run_bench_shadows(const BenchShadowsArgs& args);

}  // namespace voxr::cli
