// The one way to voxelize: a Voxelizer turns an uploaded mesh into a DeviceVoxelGrid with the surface
// method, rule and channels the options name, then (optionally) fills the interior, all on the device and on
// one upload. Which method runs is decided here, in one table (kMethods) and one factory.
//
// Methods (the surface set; every method gives occ, the slice family also count, normal, material):
//   hybrid    default: small triangles voxelized directly, one work item each (vox_direct.cl, Schwarz &
//             Seidel 2010 §3's triangle-parallel pass); triangles whose cell range exceeds 16 per axis or
//             1024 in all take the papers' slice duplication below. Same voxels as `slice`.
//   slice     Chang & Lai (TR 1688, PG 2011): every triangle duplicated once per slab and block of rows
//             (vox_setup -> scan -> expand_copies, the geometry shader's duplication) and
//             scanline-rasterized (vox_raster). Kept as the papers' method for Table 1.
//   grid      Llamas 2007 ("Grid" in the papers' Table 1): one launch per slab over every triangle.
//   slicemap  Eisemann & Decoret 2006: bit columns, centre sampling; occupancy only.
// Rules (slice family): conservative (every voxel whose closed box meets the closed input triangle; boxes
// are widened by the snap bound, host/voxelize/snapped_triangle.h, so the set is a guaranteed superset of
// the exact one) or center (the papers' column-centre rule).
// Solid fill (host/voxelize/solid_fill.h): inside channel by xor, late, parity or flood.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cl/cl_runtime.h"
#include "core/grid_spec.h"
#include "core/triangle_soup.h"
#include "grid/device_voxel_grid.h"
#include "grid/voxel_grid.h"
#include "voxelize/device_mesh.h"
#include "voxelize/raster_mode.h"
#include "voxelize/slicemap_slicing.h"
#include "voxelize/solid_mode.h"

namespace voxr {

enum class VoxelizeMethod { kHybrid, kSlice, kGrid, kSlicemap };

struct MethodInfo {
  VoxelizeMethod method;
  const char* name;
  const char* summary;
  bool attributes;  // produces count, normal, material
  bool modes;       // takes --mode conservative|center
};

inline constexpr std::array<MethodInfo, 4> kMethods = {{
    {VoxelizeMethod::kHybrid, "hybrid",
     "small triangles directly, one work item each; large ones by slice duplication (default)", true, true},
    {VoxelizeMethod::kSlice, "slice", "the papers' one-pass slice duplication for every triangle", true,
     true},
    {VoxelizeMethod::kGrid, "grid", "Llamas' Grid baseline: one pass per slab over every triangle", true,
     true},
    {VoxelizeMethod::kSlicemap, "slicemap", "Eisemann & Decoret bit columns (occupancy, centre sampling)",
     false, false},
}};

// The kMethods entry of `method`.
const MethodInfo& method_info(VoxelizeMethod method);
// Throws voxr::Error naming the unknown method and listing the known ones.
VoxelizeMethod parse_voxelize_method(std::string_view name);

struct VoxelizeOptions {
  VoxelizeMethod method = VoxelizeMethod::kHybrid;
  RasterMode mode = RasterMode::kConservative;          // slice family
  SlicemapSlicing slicing = SlicemapSlicing::kUniform;  // slicemap
  ChannelSet channels;                                  // surface channels; inside comes with `solid`
  std::optional<SolidMode> solid;                       // fill the interior (adds the inside channel)
  uint32_t rows_per_copy = 16;                          // rows of a slab one raster work item walks
  uint64_t record_budget_bytes = 256ull << 20;          // device memory for copy/tile records per batch
  // Slice family with the count channel: also the per-voxel triangle lists (DeviceVoxelGrid::list_offsets,
  // list_ids): count -> scan -> the raster passes again writing ids -> sort (kernels/voxelize/vox_lists.cl).
  // With the conservative rule a voxel lists every triangle that touches it.
  bool triangle_lists = false;
  std::function<void(const std::string& stage)> progress;  // optional, called between stages

  // Throws voxr::Error explaining a combination the method cannot produce (slicemap with count/normal/
  // material or with a mode, inside without solid, rows_per_copy 0, triangle lists without count).
  void validate() const;
  // These options without the inside channel: what the surface voxelizer is asked for.
  VoxelizeOptions surface_only() const;
  // The channels a run produces: `channels`, plus inside with `solid`.
  ChannelSet result_channels() const;
};

// Counts and times of one run, for every method and the solid fill.
struct VoxelizeStats {
  uint64_t triangles = 0;         // voxelized (after splitting oversized triangles)
  uint64_t triangles_split = 0;   // input triangles that were split
  uint64_t direct_triangles = 0;  // hybrid: triangles voxelized by the direct pass
  uint64_t copies = 0;            // records: (triangle, slab, row block) copies or slicemap tiles
  uint64_t work_items = 0;        // raster work items: direct triangles + copies, or triangles x slabs (grid)
  uint64_t batches = 0;
  // (With deferred counts, direct_triangles, copies, work_items, batches and voxels_set are those of the
  // capacities the launches ran over: the true counts are checked after the caller's next wait.)
  uint64_t voxels_set = 0;  // known when the run builds the rank index or reads back; 0 for a device-only
                            // occupancy run (build_rank_index or read_back gives it)
  uint32_t margin = 0;      // conservative: widening of voxel boxes, 1/VOXR_SUBVOXEL voxel units
  // solid fill
  uint64_t inside_voxels = 0;
  uint64_t questionable_columns = 0;  // late: columns with an odd crossing count
  uint64_t repair_iterations = 0;     // late: repair rounds that resolved at least one column
  uint64_t flood_iterations = 0;      // flood: sweep rounds, the last one changing nothing
  uint64_t device_bytes = 0;          // device memory of the run's buffers (grid and scratch)
  double upload_ms = 0.0;             // profiled transfers and kernels
  double kernels_ms = 0.0;
  double readback_ms = 0.0;
  double wall_ms = 0.0;                    // host clock around the run, including waits
  std::map<std::string, double> stage_ms;  // profiled kernel time per stage
  double total_ms() const { return upload_ms + kernels_ms + readback_ms; }
};

// Hybrid, conservative, occupancy only, whatever the user asked for: the surface that later stages build on
// (the solid's flood fill, the sparse layout's coarse pass over bricks), which must be a superset.
VoxelizeOptions conservative_occupancy_options();

// One surface method (an entry of kMethods); the Voxelizer owns one of each it has used.
class SurfaceVoxelizer {
 public:
  virtual ~SurfaceVoxelizer() = default;
  // The programs a run with `options` builds, so they can be built before anything is timed.
  virtual std::vector<ProgramSpec> programs(const VoxelizeOptions& options) const = 0;
  // Writes the surface channels of options.channels into `out` (already reset to the grid and channels;
  // its buffers may be reused): occ, and for sparse channels the rank index, voxels_set and the channels.
  virtual void run(const DeviceMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options,
                   DeviceVoxelGrid& out, VoxelizeStats& stats) = 0;
};

// The factory of kMethods.
std::unique_ptr<SurfaceVoxelizer> make_surface_voxelizer(ClRuntime& cl, VoxelizeMethod method);

class SolidFill;

class Voxelizer {
 public:
  explicit Voxelizer(ClRuntime& cl);
  ~Voxelizer();

  // Builds (or loads from the program cache) every program a run with `options` uses.
  void prepare(const VoxelizeOptions& options);

  // Voxelizes an uploaded mesh into `out`, whose buffers are reused when large enough: the surface, then
  // the interior when options.solid is set. Nothing is read back. `stats` (optional) receives counts and
  // profiled times of this run (upload_ms stays 0: the mesh was uploaded before); without it the run does
  // not wait for the queue before it starts, and while counts are deferred (ClRuntime::counts_deferred, a
  // frame) it does not wait at its end either: the mesh must then stay alive until the caller's next wait.
  void run(const DeviceMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options, DeviceVoxelGrid& out,
           VoxelizeStats* stats = nullptr);

  // The whole job from host memory: split oversized triangles, upload, run, read back. `bounds` (optional)
  // must contain the soup's vertices. stats include the upload and the readback; wall_ms spans all of it.
  VoxelGrid run(const TriangleSoup& soup, const GridSpec& grid, const VoxelizeOptions& options,
                VoxelizeStats* stats = nullptr, const Bounds* bounds = nullptr);

  // The surface voxelizer of `method` (made on first use), e.g. to read a slicemap's raw bits.
  SurfaceVoxelizer& surface(VoxelizeMethod method);

 private:
  SolidFill& solid();  // made on first use

  ClRuntime& cl_;
  std::map<VoxelizeMethod, std::unique_ptr<SurfaceVoxelizer>> surfaces_;
  std::unique_ptr<SolidFill> solid_;
  DeviceVoxelGrid grid_;  // the result of run(soup, ...), kept for buffer reuse
};

}  // namespace voxr
