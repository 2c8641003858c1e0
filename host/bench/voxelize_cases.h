// One description of each voxelization benchmark case, shared by `voxr bench voxelize` (fresh-process and
// per-frame figures), the Google Benchmark (bench/voxelize_bench.cpp) and the tests
// (tests/voxelize_cases_test.cpp runs every case on a small mesh against the CPU reference), so what is
// timed is what is proven right.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "voxelize/voxelizer.h"

namespace voxr {

struct VoxelizeCase {
  std::string name;  // "occ", "count-normal", ...
  std::string method = "hybrid";
  std::string mode = "conservative";
  std::string channels = "occ";
  std::string solid;             // empty: surface only
  std::string layout = "dense";  // or "sparse" (host/voxelize/sparse_voxelizer.h)

  VoxelizeOptions options() const;
  // The same case as `voxr voxelize` flags.
  std::vector<std::string> cli_flags() const;
};

// occ, count-normal, all-channels, count-normal-color (the bench gives the mesh colours: color_by_position),
// center, slice (the papers' duplication for every triangle), solid-parity, solid-flood, and the sparse
// layout's sparse-occ and sparse-count-normal.
const std::vector<VoxelizeCase>& voxelize_cases();
// Throws voxr::Error naming an unknown case and listing the known ones.
const VoxelizeCase& find_voxelize_case(const std::string& name);

}  // namespace voxr
