// Solid voxelization modes measured side by side: for each mesh and resolution, every mode's fill time
// (profiled kernels of the solid stages, median after a warm-up; the conservative surface every run also
// produces is left out) and its missing/extra voxels against the exact inside test (closed meshes) or
// the generalized winding number (meshes with holes). Voxels on the conservative surface are where the
// boundary rules legitimately differ, so errors off that shell ("leaks") are reported too.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "cl/cl_runtime.h"

namespace voxr {

struct SolidTableOptions {
  std::vector<std::string> meshes = {"torus", "bunny", "holed-sphere", "shark"};  // bench meshes
  std::vector<uint32_t> resolutions = {64, 128};
  int repeat = 3;
  int warmup = 1;
  std::function<void(const std::string&)> progress;
};

struct SolidTableRow {
  std::string mesh, mode, reference;  // reference: "exact" or "winding"
  bool closed = false;
  uint64_t triangles = 0;
  uint32_t res = 0;
  double kernels_ms = 0.0;
  uint64_t inside = 0, reference_inside = 0, missing = 0, extra = 0, leak_missing = 0, leak_extra = 0;
};

std::vector<SolidTableRow> run_solid_table(ClRuntime& cl, const SolidTableOptions& options);
std::string solid_table_csv(const std::vector<SolidTableRow>& rows, const std::string& device);
std::string solid_table_markdown(const std::vector<SolidTableRow>& rows, const std::string& device);

}  // namespace voxr
