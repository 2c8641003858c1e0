#include "voxelize/voxelize_job.h"

#include <fmt/format.h>

#include <cctype>
#include <cmath>

#include "cl/cl_runtime.h"
#include "core/mesh_topology.h"
#include "util/error.h"
#include "voxelize/solid_mode.h"

namespace voxr {

VoxelizeOptions make_voxelize_options(const VoxelizeChoice& choice) {
  VoxelizeOptions options;
  options.method = parse_voxelize_method(choice.method);
  const MethodInfo& info = method_info(options.method);
  if (!info.modes && !choice.mode.empty())
    fail("mode does not apply to method {} (it samples column centres)", info.name);
  if (options.method != VoxelizeMethod::kSlicemap && !choice.slicing.empty())
    fail("slicing applies to method slicemap only");
  options.slicing = parse_slicemap_slicing(choice.slicing.empty() ? "uniform" : choice.slicing);
  options.mode = parse_raster_mode(choice.mode.empty() ? "conservative" : choice.mode);
  options.channels = ChannelSet::parse(choice.channels);
  if (!choice.solid.empty()) options.solid = parse_solid_mode(choice.solid);
  options.rows_per_copy = choice.rows_per_copy;
  options.validate();
  return options;
}

VoxelizeInput prepare_voxelize_input(Scene&& scene, VoxelizeOptions& options) {
  std::vector<std::string> warnings;
  for (const MeshInstance& m : scene.meshes)
    warnings.insert(warnings.end(), m.warnings.begin(), m.warnings.end());
  warnings.insert(warnings.end(), scene.warnings.begin(), scene.warnings.end());
  TriangleSoup soup = take_scene_triangles(scene);
  return prepare_voxelize_input(std::move(soup), scene.source, scene.grid, std::move(warnings), options,
                                false);
}

VoxelizeInput prepare_voxelize_input(TriangleSoup&& soup, const std::string& source,
                                     const GridRequest& request, std::vector<std::string> warnings,
                                     VoxelizeOptions& options, bool validated, const Bounds* bounds) {
  VoxelizeInput in;
  in.source = source;
  in.request = request;
  in.warnings = std::move(warnings);
  in.soup = std::move(soup);
  if (!validated) in.degenerate = validate_soup(in.soup, source);
  if (options.channels.has(Channel::kColor) && in.soup.colors.empty())
    in.warnings.push_back(fmt::format("{} has no colours; the color channel is white", source));
  in.bounds = bounds ? *bounds : in.soup.bounds();
  if (options.solid) {
    // Closure is judged on welded positions; a triangle listed twice would flip every column parity
    // through it, and the winding-number definition of inside ignores the copy, so copies go.
    const MeshTopology topology = mesh_topology(in.soup);
    if (topology.duplicates > 0) {
      drop_duplicate_triangles(in.soup);
      in.warnings.push_back(
          fmt::format("{}: {} triangles repeat an earlier triangle exactly (first: triangle {}); the copies "
                      "were dropped",
                      source, topology.duplicates, topology.first_duplicate));
    }
    if (!topology.closed() && (options.solid == SolidMode::kParity || options.solid == SolidMode::kXor)) {
      // Column parity needs a closed surface. Late filling repairs the columns that cross a hole from their
      // neighbours: on the holed test meshes it stays within a few voxels of the winding-number reference,
      // where flood fill loses the interior once a hole is wider than a voxel (bench/results/solid-*).
      in.warnings.push_back(
          fmt::format("{} is not closed ({}); solid {} would leak through the holes, using "
                      "solid late",
                      source, topology.describe(in.soup.anchor), solid_mode_name(*options.solid)));
      options.solid = SolidMode::kLate;
      in.solid_switched = true;
    }
  }
  return in;
}

GridRequest choose_grid_request(GridRequest request, const GridChoice& choice) {
  if (choice.resolution && choice.dims) fail("resolution and dims are exclusive; give one");
  if (choice.resolution) {
    request.resolution = choice.resolution;
    request.dims.reset();
  }
  if (choice.dims) request.dims = choice.dims;
  if (choice.bounds) request.bounds = choice.bounds;
  return request;
}

uint64_t parse_memory_size(const std::string& text, const std::string& what) {
  size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    fail("{} '{}': expected a size such as 512M or 2G", what, text);
  }
  std::string suffix = text.substr(used);
  for (char& c : suffix) c = char(std::toupper(static_cast<unsigned char>(c)));
  if (!suffix.empty() && suffix.back() == 'B' && suffix.size() <= 3 && suffix != "B") suffix.pop_back();
  if (suffix.size() == 2 && suffix[1] == 'I') suffix.pop_back();  // 2GiB, 2Gi
  const std::string units = "KMGT";
  double scale = 1.0;
  if (!suffix.empty() && suffix != "B") {
    const size_t at = units.find(suffix);
    if (suffix.size() != 1 || at == std::string::npos)
      fail("{} '{}': unknown unit '{}' (use K, M, G or T)", what, text, text.substr(used));
    scale = std::ldexp(1.0, 10 * int(at + 1));
  }
  const double bytes = value * scale;
  if (!(bytes >= double(1 << 20)) || bytes > 1e18) fail("{} '{}': give at least 1M", what, text);
  return uint64_t(bytes);
}

GridLayout parse_grid_layout(const std::string& name, const std::string& what) {
  if (name == "auto") return GridLayout::kAuto;
  if (name == "dense") return GridLayout::kDense;
  if (name == "sparse") return GridLayout::kSparse;
  fail("{} '{}': expected auto, dense or sparse", what, name);
}

bool choose_sparse_layout(GridLayout layout, const GridSpec& grid, const VoxelizeOptions& options,
                          const ClRuntime& cl) {
  if (layout == GridLayout::kDense) return false;
  if (layout == GridLayout::kSparse) {
    SparseVoxelizer::validate(options);
    return true;
  }
  const uint64_t dense = dense_occupancy_bytes(grid.dims);
  if (dense <= kDenseLayoutLimitBytes && dense <= cl.device().max_allocation) return false;
  try {
    SparseVoxelizer::validate(options);
  } catch (const Error&) {
    return false;  // solid fill, slicemap, lists: dense, which says so itself if the grid does not fit
  }
  return true;
}

VoxelizeResult run_voxelize_job(ClRuntime& cl, Voxelizer& voxelizer, std::unique_ptr<SparseVoxelizer>& bricks,
                                const VoxelizeInput& input, const GridSpec& grid,
                                const VoxelizeOptions& options, GridLayout layout, uint64_t memory_budget,
                                bool bounds_given) {
  VoxelizeResult r;
  r.sparse = choose_sparse_layout(layout, grid, options, cl);
  if (r.sparse) {
    if (!bricks) bricks = std::make_unique<SparseVoxelizer>(cl);
    r.sparse_stats.emplace();
    r.bricks =
        bricks->run(input.soup, grid, options, memory_budget, &r.stats, &*r.sparse_stats, &input.bounds);
  } else {
    r.dense = voxelizer.run(input.soup, grid, options, &r.stats, &input.bounds);
    if (memory_budget)
      r.warnings.push_back(
          fmt::format("the memory budget applies to the sparse layout; the {} x {} x {} grid ran dense",
                      grid.dims.x, grid.dims.y, grid.dims.z));
  }
  // An empty volume is the right answer for a grid beside the mesh, never a silent one.
  if (r.stats.voxels_set == 0 && r.stats.inside_voxels == 0)
    r.warnings.push_back(fmt::format("no voxel of the {} x {} x {} grid touches {}{}", grid.dims.x,
                                     grid.dims.y, grid.dims.z, input.source,
                                     bounds_given ? " (check the bounds)" : ""));
  return r;
}

nlohmann::json voxelize_report(const std::string& input, const ClRuntime& cl, const GridSpec& grid,
                               const VoxelizeOptions& options, const VoxelizeResult& result) {
  const VoxelizeStats& stats = result.stats;
  nlohmann::json stages = nlohmann::json::object();
  for (const auto& [name, ms] : stats.stage_ms) stages[name] = ms;
  const uint64_t host_bytes = result.host_bytes();
  nlohmann::json report = {
      {"input", input},
      {"device", cl.device().label()},
      {"driver", cl.device().driver_version},
      {"method", method_info(options.method).name},
      {"mode", options.method == VoxelizeMethod::kSlicemap ? "center" : raster_mode_name(options.mode)},
      {"channels", result.channels().to_string()},
      {"triangles", stats.triangles},
      {"triangles_split", stats.triangles_split},
      {"direct_triangles", stats.direct_triangles},
      {"dims", {grid.dims.x, grid.dims.y, grid.dims.z}},
      {"voxel_size", grid.voxel_size},
      {"origin",
       {grid.anchor.x + grid.origin.x, grid.anchor.y + grid.origin.y, grid.anchor.z + grid.origin.z}},
      {"margin", stats.margin},
      {"copies", stats.copies},
      {"batches", stats.batches},
      {"voxels_set", stats.voxels_set},
      {"device_bytes", stats.device_bytes},
      {"layout", result.sparse ? "sparse" : "dense"},
      {"host_bytes", host_bytes},
      {"ms",
       {{"upload", stats.upload_ms},
        {"kernels", stats.kernels_ms},
        {"readback", stats.readback_ms},
        {"total", stats.total_ms()},
        {"wall", stats.wall_ms},
        {"stages", stages}}},
  };
  if (result.sparse_stats) {
    const SparseStats& s = *result.sparse_stats;
    const auto per_voxel = [&](uint64_t bytes) {
      return stats.voxels_set ? double(bytes) / double(stats.voxels_set) : 0.0;
    };
    report["sparse"] = {{"brick", kBrickEdge},
                        {"slabs", s.slabs},
                        {"bricks_marked", s.bricks_marked},
                        {"bricks", s.bricks_kept},
                        {"memory_budget", s.memory_budget},
                        {"peak_device_bytes", s.peak_device_bytes},
                        {"peak_grid_bytes", s.peak_grid_bytes},
                        {"grid_bytes_per_voxel", per_voxel(s.peak_grid_bytes)},
                        {"device_bytes_per_voxel", per_voxel(s.peak_device_bytes)},
                        {"host_bytes_per_voxel", per_voxel(host_bytes)}};
  }
  if (options.method == VoxelizeMethod::kSlicemap) report["slicing"] = slicemap_slicing_name(options.slicing);
  if (options.solid)
    report["solid"] = {{"mode", solid_mode_name(*options.solid)},
                       {"inside_voxels", stats.inside_voxels},
                       {"questionable_columns", stats.questionable_columns},
                       {"repair_iterations", stats.repair_iterations},
                       {"flood_iterations", stats.flood_iterations}};
  return report;
}

}  // namespace voxr
