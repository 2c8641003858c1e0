// The animation benchmark (`voxr bench animation`): the frame rate of deforming scenes, every frame posed and
// re-voxelized. Per scene, `frames` consecutive frames at t = f / fps with the default methods (voxel
// shadows, centre mode, 256 columns; voxel-multi refraction at res 256 when the scene has glass):
//   frame    wall time of FrameRenderer::render (light grid fit, voxelize from the light, the refraction
//            grid, camera raster, refraction, lookup, shade, image read back): median, min, max and the
//            frame rate 1000 / median;
//   pose     host posing of the scene (core/animation.h) plus set_scene (upload, vertex normals): median;
//   stages   the profiled device time of each stage, medians over the frames;
//   fresh    `voxr render SCENE --frames N` as a new process, timed by the caller.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "bench/shadow_bench.h"
#include "cl/cl_runtime.h"

namespace voxr {

struct AnimationBenchOptions {
  std::vector<std::string> scenes = {"data/scenes/swaying-tree.json", "data/scenes/morphing-glass.json",
                                     "data/scenes/passing-objects.json"};
  int frames = 48;
  glm::uvec2 size{640, 480};  // the image
};

struct AnimationBenchRow {
  std::string scene, refraction;
  uint64_t triangles = 0;
  double fps_scene = 0;  // the scene's frames per second (animation time)
  double frame_ms = 0, frame_min = 0, frame_max = 0, pose_ms = 0;
  std::map<std::string, double> stages;  // medians
  double fresh_ms = -1;                  // median wall ms of the fresh processes; -1: none
};

// "name ms" of every stage with a positive time, joined by `separator`.
std::string stage_text(const std::map<std::string, double>& stages, const char* separator);

// Runs the measurements on `cl`'s device, printing one line per scene; `fresh` (optional) times `voxr
// render SCENE --frames N` after each scene. Throws voxr::Error for an unreadable scene or one that is not
// animated.
std::vector<AnimationBenchRow> measure_animation(ClRuntime& cl, const AnimationBenchOptions& options,
                                                 const FreshRenders& fresh = {});

}  // namespace voxr
