// The shadow benchmark (`voxr bench shadows`, `bench pareto`): every shadow method x shadow resolution x
// scene, time against error, in one run. Per scene, the camera's samples are the same for every method (one
// kernel rasterizer), so the exact shadows at them are traced once with Embree (eval/reference_comparison.h)
// and every method is measured against them:
//   frame    warm per-frame wall time of FrameRenderer::render (light grid fit, voxelize from the light or
//            rasterize the light maps, accumulate, camera raster + resolve, lookup, shade, image read back),
//            median with min and max of `repeat` frames after `warmup`;
//   error    transmittance RMSE and maximum over the visible receivers, share of receivers off by > 0.05,
//            PSNR of the shaded image against the same samples shaded with the exact transmittance;
//   reference  Embree's frame for a deforming scene: BVH rebuild + the same shadow rays (+ shading), as
//            measured here on the host's cores;
//   fresh    `voxr render SCENE --shadows voxel --shadow-res 256` as a new process, timed by the caller.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "cl/cl_runtime.h"
#include "metrics/image_metrics.h"

namespace voxr {

struct ShadowBenchOptions {
  std::vector<std::string> scenes = {"default", "data/scenes/shadow-tree.json", "data/scenes/foliage.json",
                                     "data/scenes/glass-floor.json"};
  std::vector<uint32_t> resolutions = {64, 128, 256, 512};
  std::vector<std::string> methods = {"voxel-center", "voxel-conservative", "uniform", "filter",
                                      "opaque",       "voxel-exact"};
  glm::uvec2 size{640, 480};  // the image
  int repeat = 5;
  int warmup = 1;
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

// Wall ms of fresh `voxr render RENDER_ARGS` processes (the CLI starts them: cli/bench_support.h).
using FreshRenders = std::function<std::vector<double>(const std::vector<std::string>& render_args)>;

// One scene's fresh processes.
struct FreshRenderTimes {
  std::string scene;  // its label
  uint64_t triangles = 0;
  std::vector<double> wall_ms;
};

struct ShadowBenchRun {
  std::vector<ShadowBenchRow> rows;     // per scene: the reference, then methods x resolutions
  std::vector<FreshRenderTimes> fresh;  // per scene, when a FreshRenders was given
};

// Runs the measurements on `cl`'s device, printing one line per case; `fresh` (optional) times
// `voxr render SCENE --shadows voxel --shadow-res 256` after each scene. Throws voxr::Error for an unknown
// method or an unreadable scene.
ShadowBenchRun measure_shadows(ClRuntime& cl, const ShadowBenchOptions& options,
                               const FreshRenders& fresh = {});

}  // namespace voxr
