// One `voxr voxelize` job after the input is read: the steps the CLI and the public API (host/api) share, so
// the same input and settings give the same voxels through either: take and check the scene's triangles,
// fit the grid the user asked for, prepare a solid fill (drop repeated triangles; parity and xor give way to
// late filling on an open mesh), choose the layout, run, and describe the run as the --report object.
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

#include "core/grid_spec.h"
#include "core/scene.h"
#include "grid/sparse_voxel_grid.h"
#include "grid/voxel_grid.h"
#include "voxelize/sparse_voxelizer.h"
#include "voxelize/voxelizer.h"

namespace voxr {

class ClRuntime;

// The method and what it writes, by the names the CLI's flags and the public API use (docs/cli.md): method
// hybrid|slice|grid|slicemap, mode conservative|center (empty: conservative), slicing uniform|local (slicemap
// only; empty: uniform), channels "occ,count,...", solid xor|late|parity|flood (empty: surface only).
struct VoxelizeChoice {
  std::string method = "hybrid";
  std::string mode;
  std::string slicing;
  std::string channels = "occ";
  std::string solid;
  uint32_t rows_per_copy = 16;  // VoxelizeOptions::rows_per_copy
};
// Throws voxr::Error naming the option for an unknown name or a combination that does not apply.
VoxelizeOptions make_voxelize_options(const VoxelizeChoice& choice);

// The scene's triangles, ready to voxelize. `warnings` holds what the CLI prints as "voxr: warning: ...",
// one line each, starting with the file or mesh they are about.
struct VoxelizeInput {
  TriangleSoup soup;
  Bounds bounds;                // of the soup's triangles, relative to soup.anchor
  std::string source;           // the scene's file, or the caller's name for the mesh
  GridRequest request;          // the scene's grid request (a scene file's "grid"), before the user's choices
  size_t degenerate = 0;        // zero-area triangles (kept)
  bool solid_switched = false;  // options.solid was changed to late (an open mesh)
  std::vector<std::string> warnings;
};

// Takes `scene`'s triangles, validates them and prepares `options.solid` (which may change: see the file
// comment). Throws voxr::Error naming the scene's source when it has no triangles, an index out of range or a
// NaN/infinite vertex.
VoxelizeInput prepare_voxelize_input(Scene&& scene, VoxelizeOptions& options);
// The same for a soup made elsewhere (the public API's arrays, soup_from_arrays): `validated` skips
// validate_soup when the maker has checked indices and positions already (degenerate then stays 0); `bounds`
// (optional): soup.bounds(), when the maker found it on the way.
VoxelizeInput prepare_voxelize_input(TriangleSoup&& soup, const std::string& source,
                                     const GridRequest& request, std::vector<std::string> warnings,
                                     VoxelizeOptions& options, bool validated,
                                     const Bounds* bounds = nullptr);

// The user's grid choices over the scene's request: resolution (voxels along the longest side; 0 keeps the
// scene's), exact dims, or world bounds. Throws voxr::Error when resolution and dims are both given.
struct GridChoice {
  uint32_t resolution = 0;
  std::optional<glm::uvec3> dims;
  std::optional<WorldBox> bounds;
};
GridRequest choose_grid_request(GridRequest scene_request, const GridChoice& choice);

// Where the grid lives: dense bits over the whole grid, 8^3 bricks where the surface is (SparseVoxelizer), or
// auto: dense up to kDenseLayoutLimitBytes of bits and the device's largest allocation, bricks beyond when
// the options allow them (not solid fill, slicemap or lists). A memory size: bytes with an optional K, M, G
// or T suffix (powers of 1024; "2G", "512MiB", "1e9"), at least 1 MiB. Throws voxr::Error starting with
// `what` (the option's name) and the text.
uint64_t parse_memory_size(const std::string& text, const std::string& what);

enum class GridLayout { kAuto, kDense, kSparse };
// "auto", "dense", "sparse"; throws voxr::Error starting with `what` (the option's name) and the text.
GridLayout parse_grid_layout(const std::string& name, const std::string& what);
constexpr uint64_t kDenseLayoutLimitBytes = uint64_t(512) << 20;
// True when `layout` runs `grid` in bricks. Throws voxr::Error when kSparse is asked for options it cannot
// run.
bool choose_sparse_layout(GridLayout layout, const GridSpec& grid, const VoxelizeOptions& options,
                          const ClRuntime& cl);

// A finished run: the dense grid or the bricks (by `sparse`), its counts and times.
struct VoxelizeResult {
  bool sparse = false;
  VoxelGrid dense;
  SparseVoxelGrid bricks;
  VoxelizeStats stats;
  std::optional<SparseStats> sparse_stats;
  std::vector<std::string> warnings;  // about the run (an empty grid, a budget the dense layout ignored)

  const ChannelSet& channels() const { return sparse ? bricks.channels : dense.channels; }
  uint64_t host_bytes() const { return sparse ? bricks.memory_bytes() : dense.memory_bytes(); }
};

// Runs `input` on `grid` in the chosen layout: `voxelizer` for dense grids, `bricks` (made on first need) for
// sparse ones; memory_budget 0 = default_memory_budget; bounds_given: the user chose the grid's bounds (an
// empty grid's warning then says to check them). Throws what the voxelizers throw (voxr::Error for a
// grid the device cannot hold).
VoxelizeResult run_voxelize_job(ClRuntime& cl, Voxelizer& voxelizer, std::unique_ptr<SparseVoxelizer>& bricks,
                                const VoxelizeInput& input, const GridSpec& grid,
                                const VoxelizeOptions& options, GridLayout layout, uint64_t memory_budget,
                                bool bounds_given);

// The run as the --report object (docs/cli.md): input, device, method, counts, grid, memory, `ms` (the run's
// own times; the CLI adds the process phases), sparse and solid details.
nlohmann::json voxelize_report(const std::string& input, const ClRuntime& cl, const GridSpec& grid,
                               const VoxelizeOptions& options, const VoxelizeResult& result);

}  // namespace voxr
