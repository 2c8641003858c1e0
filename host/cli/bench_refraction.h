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
                                      "image-space"};
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

int run_bench_refraction(const BenchRefractionArgs& args);

}  // namespace voxr::cli
