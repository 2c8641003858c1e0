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

int run_bench_shadows(const BenchShadowsArgs& args);

}  // namespace voxr::cli
