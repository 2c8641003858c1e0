// voxr bench voxelize: what a user gets, and what a frame costs. For every mesh x resolution x case
// (host/bench/voxelize_cases.h) it measures, side by side in one run:
//   fresh   `voxr voxelize MESH.off --res R ...` started as a new process (the mesh written to a temporary
//           OFF file first), `fresh` times: the process's wall time measured from here, and the report's
//           ms.wall (mesh in host memory -> grid on the host) and ms.process;
//   job     the same job in this (warm) process: upload + voxelize + readback, wall time;
//   frame   the per-frame case: the mesh uploaded once, voxelized again into a grid that stays on the
//           device; profiled kernel time and wall time.
// Medians with min and max; triangles and voxels per second of frame kernel time; the 1-minute load
// average before and after each case (the machine must be quiet for the numbers to mean anything).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace voxr::cli {

struct BenchVoxelizeArgs {
  std::vector<std::string> meshes = {"torus", "bunny", "bunnyx16"};
  std::vector<uint32_t> resolutions = {256, 512, 1024};
  std::vector<std::string> cases = {"occ"};
  std::string device;
  std::string out;    // CSV
  std::string write;  // fresh processes also write -o out.<write> (e.g. binvox); empty: no output file
  int repeat = 5;     // frame and job repeats
  int warmup = 1;
  int fresh = 5;  // fresh processes per case; 0 skips them
};

int run_bench_voxelize(const BenchVoxelizeArgs& args);

}  // namespace voxr::cli
