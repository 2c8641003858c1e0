// voxr bench animation: the frame rate of deforming scenes, every frame posed and re-voxelized. Per scene,
// `frames` consecutive frames at t = f / fps with the default methods (voxel shadows, centre mode, 256
// columns; voxel-multi refraction at res 256 when the scene has glass):
//   frame    wall time of FrameRenderer::render (light grid fit, voxelize from the light, the refraction
//            grid, camera raster, refraction, lookup, shade, image read back): median, min, max and the
//            frame rate 1000 / median;
//   pose     host posing of the scene (core/animation.h) plus set_scene (upload, vertex normals): median;
//   stages   the profiled device time of each stage, medians over the frames;
//   fresh    `voxr render SCENE --frames N --size SIZE` as a new process (opening the device, the cached
//            programs, reading the scene, N frames, the last image written), `fresh` times.
// Writes OUT.csv and OUT.md (with the date, the command and the load average).
#pragma once

#include <string>
#include <vector>

namespace voxr::cli {

struct BenchAnimationArgs {
  std::vector<std::string> scenes = {"data/scenes/swaying-tree.json", "data/scenes/morphing-glass.json",
                                     "data/scenes/passing-objects.json"};
  int frames = 48;
  std::string size = "640x480";
  std::string device;
  std::string out = "animation";
  int fresh = 1;
};

int run_bench_animation(const BenchAnimationArgs& args);

}  // namespace voxr::cli
