// voxr bench refraction: every refraction method x grid resolution x scene, frame time against error, in one
// run. Per scene:
//   reference  the matched Embree reference (reference_refraction.h), rendered once: its frame time is the
//            BVH build + tracing the refracted paths + the shadow rays + shading, on the host's cores (one
//            row, method "reference-matched");
//   frame    warm per-frame wall time of FrameRenderer::render with the chosen shadows (voxelize the scene
//            with normals and inside + rasterize + refract + shadows + shade, image read back), median with
//            min and max of `repeat` frames after `warmup`; the "refraction" stage is the trace kernel alone;
//   error    one more frame of the same method with the exact (Embree) shadow transmittance at its path
//            ends, so that the error is refraction's alone, against the matched reference: image RMSE and
//            PSNR, exit direction angle mean and 95th percentile, event sequence mismatches, non-finite
//            pixels (metrics/refraction_metrics.h);
//   fresh    `voxr render SCENE --refraction voxel-multi --res 256` (same shadows and size) as a new
//            process, `fresh` times.
// Image-space refraction has no grid: it runs once per scene (res empty); Wyman's d_N is ray cast once per
// scene before it, as the paper precomputes it offline (its time is in the Markdown, not in the frame).
// Writes OUT.csv and OUT.md, then the charts (bench/shadow_charts.py: time against rmse and against
// angle_mean_deg) into OUT-charts/rmse/ and OUT-charts/angle_mean_deg/ when python3 and matplotlib are there.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cl/cl_runtime.h"
#include "metrics/refraction_metrics.h"

namespace voxr::cli {

struct BenchRefractionArgs {
  std::vector<std::string> scenes = {"data/scenes/glass-sphere.json", "data/scenes/bunny-glass-130.json",
                                     "data/scenes/glass-vase.json",   "data/scenes/ball-figure.json",
                                     "data/scenes/gem.json",          "data/scenes/thin-shell.json",
                                     "data/scenes/sphere-nearby.json"};
  std::vector<std::string> methods = {"voxel-multi-dda-smooth",
                                      "voxel-multi-dda-voxel",
                                      "voxel-multi-papers-smooth",
                                      "voxel-multi-papers-voxel",
                                      "voxel-two",
                                      "image-space",
                                      "distance-maps"};
  std::vector<uint32_t> resolutions = {64, 128, 256, 512};
  std::string shadows = "voxel";
  uint32_t shadow_res = 256;
  std::string size = "640x480";
  std::string device;
  std::string out = "refraction";
  int repeat = 5;
  int warmup = 1;
  int fresh = 3;
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

struct RefractionBenchRun {
  std::vector<RefractionBenchRow> rows;  // per scene: the reference, then methods x resolutions
  std::string fresh_table;               // Markdown rows of the fresh processes (empty when args.fresh is 0)
  std::string precompute_table;          // Markdown rows of image-space's d_N ray casting per scene
};

// Throws voxr::Error naming what is wrong when a method, the shadow method, the size or a scene file is not
// valid; touches no device.
void check_bench_refraction_args(const BenchRefractionArgs& args);

// Runs the measurements on `cl`'s device, printing one line per case. args.out is not used. Throws as
// check_bench_refraction_args does.
RefractionBenchRun measure_refraction(ClRuntime& cl, const BenchRefractionArgs& args);

// measure_refraction, then OUT.csv, OUT.md and the charts.
int run_bench_refraction(const BenchRefractionArgs& args);

}  // namespace voxr::cli
