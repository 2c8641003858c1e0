// The papers' Table 1, extended: every voxelization method over meshes with the papers' triangle counts and
// several resolutions, each case timed (medians after a warm-up, from profiling events) and measured for
// accuracy against the exact triangle/box set of the input triangles (host/voxelize/reference_overlap.h,
// measured by host/voxelize/surface_accuracy.h).
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "cl/cl_runtime.h"
#include "core/grid_spec.h"
#include "core/triangle_soup.h"
#include "voxelize/voxelizer.h"

namespace voxr {

struct Table1Model {
  std::string label;  // as in the papers' table: "Torus", "~43K", ...
  std::string mesh;   // bench_meshes name
};

// A method from outside voxr_core (a CPU peer such as OpenVDB): voxelizes and fills stats->kernels_ms.
using Table1Peer = std::function<VoxelGrid(const TriangleSoup&, const GridSpec&, VoxelizeStats*)>;

// A distance of a voxelization from its triangles (e.g. metrics/voxel_surface_error.h's chamfer, relative to
// the scene's size), measured on the last timed run of each case.
using Table1SurfaceError = std::function<double(const VoxelGrid&, const GridSpec&, const TriangleSoup&)>;

struct Table1Options {
  std::vector<Table1Model> models;
  std::vector<uint32_t> resolutions = {128, 256, 512};
  std::vector<std::string> methods;  // table1_methods() or names in `peers`
  std::map<std::string, Table1Peer> peers;
  int repeat = 3;
  int warmup = 1;
  bool accuracy = true;
  Table1SurfaceError surface_error;                  // empty: not measured (Table1Row::surface_error NaN)
  std::function<void(const std::string&)> progress;  // one line per finished case
};

struct Table1Row {
  std::string model, mesh, method;
  uint64_t triangles = 0;
  uint32_t res = 0;
  std::string dims;
  double kernels_ms = 0.0, total_ms = 0.0;  // medians; total = upload + kernels + readback
  double kernels_min_ms = 0.0, kernels_max_ms = 0.0;
  uint64_t grid_bytes = 0;  // the dense occupancy bits read back
  uint64_t voxels = 0;
  uint64_t exact_voxels = 0, false_positives = 0, false_negatives = 0, crossings = 0, tunnels = 0;
  double surface_error = std::numeric_limits<double>::quiet_NaN();  // Table1Options::surface_error's
};

// "hybrid-conservative", "slice-conservative", "slice-center", "grid", "slicemap-uniform", "slicemap-local".
const std::vector<std::string>& table1_methods();
// The voxelizer options of a core method name of table1_methods() (peers are not voxelizer options).
VoxelizeOptions table1_voxelize_options(const std::string& method);
// Torus 800, ~43K (armadillo), ~97K (elephant), ~655K (shark x64), ~871K (armadillo x16), ~1.09M (bunny x16).
std::vector<Table1Model> table1_default_models();

std::vector<Table1Row> run_table1(ClRuntime& cl, const Table1Options& options);

std::string table1_csv(const std::vector<Table1Row>& rows, const std::string& device);
// Shaped like the papers' table: one line per model, one column per resolution x method (ms).
std::string table1_markdown(const std::vector<Table1Row>& rows, const std::string& device);

}  // namespace voxr
