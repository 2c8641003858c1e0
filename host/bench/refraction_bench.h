// The refraction benchmark (`voxr bench refraction`, `bench pareto`): every refraction method x grid
// resolution x scene, frame time against error, in one run. Per scene:
//   reference  the matched Embree reference (reference_refraction.h), rendered once: its frame time is the
//            BVH build + tracing the refracted paths + the shadow rays + shading, on the host's cores (one
//            row, method "reference-matched");
//   frame    warm per-frame wall time of FrameRenderer::render with the chosen shadows (voxelize the scene
//            with normals and inside + rasterize + refract + shadows + shade, image read back), median with
//            min and max of `repeat` frames after `warmup`; the "refraction" stage is the trace kernel alone;
//   error    one more frame of the same method with the exact (Embree) shadow transmittance at its path
//            ends, so that the error is refraction's alone, against the matched reference: image RMSE and
//            PSNR, exit direction angle mean and 95th percentile, event sequence mismatches, non-finite
//            pixels (eval/reference_comparison.h, metrics/refraction_metrics.h);
//   fresh    `voxr render SCENE --refraction <the default> --res 256` (same shadows) as a new process, timed
//            by the caller.
// Image-space refraction has no grid: it runs once per scene (res empty); Wyman's d_N is ray cast once per
// scene before it, as the paper precomputes it offline (its time is reported apart, not in the frame).
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "bench/shadow_bench.h"
#include "cl/cl_runtime.h"
#include "metrics/refraction_metrics.h"
#include "render/shadow_method.h"

namespace voxr {

// The method labels measure_refraction takes, for help texts.
extern const char* const kRefractionBenchMethodHelp;

struct RefractionBenchOptions {
  std::vector<std::string> scenes = {"data/scenes/glass-sphere.json", "data/scenes/bunny-glass-130.json",
                                     "data/scenes/glass-vase.json",   "data/scenes/ball-figure.json",
                                     "data/scenes/gem.json",          "data/scenes/thin-shell.json",
                                     "data/scenes/sphere-nearby.json"};
  std::vector<std::string> methods = {"voxel-multi-dda-smooth",
                                      "voxel-multi-dda-voxel",
                                      "voxel-multi-papers-smooth",
                                      "voxel-multi-papers-voxel",
                                      "voxel-two",
                                      "voxel-exact",
                                      "image-space",
                                      "distance-maps"};
  std::vector<uint32_t> resolutions = {64, 128, 256, 512};
  std::string shadows{shadow_method_info(kDefaultShadowMethod).name};  // the timed frames'; errors: exact
  uint32_t shadow_res = 256;
  glm::uvec2 size{640, 480};  // the image
  int repeat = 5;
  int warmup = 1;
};

// One measured case: a method at a grid resolution on a scene, or the scene's matched reference (method
// "reference-matched").
struct RefractionBenchRow {
  std::string scene, method, step, normals;  // step, normals: empty without a grid
  uint64_t triangles = 0;
  uint32_t resolution = 0;                            // 0: no grid (image-space, the reference)
  double frame_ms = 0, frame_min = 0, frame_max = 0;  // warm frame wall ms: median, min, max
  double refraction_ms = 0;                           // the trace kernel alone, median
  double layers_ms = 0;     // distance-maps: rendering the layers (the "dm-layers" stage), median
  RefractionError error{};  // against the matched reference, exact shadows
  uint64_t grid_bytes = 0;
  double load = 0;  // 1-minute load average when the case finished
};

// Image-space's per-scene precompute (Wyman's d_N, ray cast) on one scene.
struct PrecomputeTime {
  std::string scene;  // its label
  uint64_t triangles = 0;
  double ms = 0;
};

struct RefractionBenchRun {
  std::vector<RefractionBenchRow> rows;    // per scene: the reference, then methods x resolutions
  std::vector<FreshRenderTimes> fresh;     // per scene, when a FreshRenders was given
  std::vector<PrecomputeTime> precompute;  // per scene, when image-space is among the methods
};

// Throws voxr::Error naming what is wrong when a method, the shadow method or a scene file is not valid;
// touches no device.
void check_refraction_bench(const RefractionBenchOptions& options);

// Runs the measurements on `cl`'s device, printing one line per case; `fresh` (optional) times `voxr render
// SCENE --refraction <the default> --res 256 --shadows S --shadow-res R` after each scene. Throws as
// check_refraction_bench does.
RefractionBenchRun measure_refraction(ClRuntime& cl, const RefractionBenchOptions& options,
                                      const FreshRenders& fresh = {});

}  // namespace voxr
