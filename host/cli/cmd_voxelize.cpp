// voxr voxelize INPUT -o OUT: mesh or scene -> voxel grid (any method, rule, channels and solid fill, on one
// upload), written by extension, with a summary (and optional JSON report) of counts, memory and times.
//
// A fresh process pays only what it must: the OpenCL runtime is opened and every program the run needs is
// built (or loaded from the program cache) on a second thread while the mesh is read, and the timed
// voxelization starts after both.
#include <fmt/format.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>
#include <optional>

#include "cl/cl_runtime.h"
#include "cli/commands.h"
#include "cli/option_groups.h"
#include "cli/parse_args.h"
#include "cli/prepared_runtime.h"
#include "cli/process.h"
#include "core/default_scene.h"
#include "core/mesh_loader.h"
#include "core/mesh_topology.h"
#include "core/resolution_search.h"
#include "core/scene.h"
#include "io/atomic_file.h"
#include "io/volume_writer.h"
#include "metrics/voxel_surface_error.h"
#include "util/clock.h"
#include "voxelize/sparse_voxelizer.h"
#include "voxelize/voxelizer.h"

namespace voxr::cli {

namespace {

struct VoxelizeArgs {
  std::string input;  // empty: the built-in default scene
  std::string output;
  uint32_t res = 0;
  std::string dims, bounds;
  std::string method = "hybrid";
  std::string mode;     // empty: conservative
  std::string slicing;  // empty: uniform (slicemap)
  std::string solid;    // empty: surface only
  std::string channels = "occ";
  std::string device;
  std::string report;
  std::string layout = "auto";
  std::string memory_budget;           // empty: from the device
  uint32_t rows_per_copy = 16;         // VoxelizeOptions::rows_per_copy
  std::optional<double> error_target;  // the surface error to meet (voxel_surface_error.h, chamfer)
  bool profile = false;
  bool quiet = false;
  bool view = false;
};

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  return ext;
}

// --view: voxr-view is this executable's neighbour (CMake puts both in the build folder).
std::filesystem::path find_viewer(const std::string& output) {
  if (output.empty()) fail("--view needs -o OUT: the viewer opens the written volume");
  const std::string ext = lower_extension(output);
  if (ext != ".vti" && ext != ".nrrd" && ext != ".vdb")
    fail("--view: voxr-view reads .vti, .nrrd and .vdb outputs, not '{}'", output);
  const std::filesystem::path viewer = executable_folder() / "voxr-view";
  std::error_code ec;
  if (!std::filesystem::exists(viewer, ec))
    fail("--view: {} not found (configure with -DVOXR_BUILD_VIEWER=ON and build it)", viewer.string());
  return viewer;
}

// Options from the flags, validated before any file is read.
VoxelizeOptions voxelize_options(const VoxelizeArgs& args) {
  VoxelizeOptions options;
  options.method = parse_voxelize_method(args.method);
  const MethodInfo& info = method_info(options.method);
  if (!info.modes && !args.mode.empty())
    fail("--mode does not apply to --method {} (it samples column centres)", info.name);
  if (options.method != VoxelizeMethod::kSlicemap && !args.slicing.empty())
    fail("--slicing applies to --method slicemap only");
  options.slicing = parse_slicemap_slicing(args.slicing.empty() ? "uniform" : args.slicing);
  options.mode = parse_raster_mode(args.mode.empty() ? "conservative" : args.mode);
  options.channels = ChannelSet::parse(args.channels);
  if (!args.solid.empty()) options.solid = parse_solid_mode(args.solid);
  options.rows_per_copy = args.rows_per_copy;
  options.validate();
  return options;
}

// --memory-budget: bytes with an optional K, M, G or T suffix (powers of 1024).
uint64_t parse_memory_budget(const std::string& text) {
  size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    fail("--memory-budget '{}': expected a size such as 512M or 2G", text);
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
      fail("--memory-budget '{}': unknown unit '{}' (use K, M, G or T)", text, text.substr(used));
    scale = std::ldexp(1.0, 10 * int(at + 1));
  }
  const double bytes = value * scale;
  if (!(bytes >= double(1 << 20)) || bytes > 1e18) fail("--memory-budget '{}': give at least 1M", text);
  return uint64_t(bytes);
}

// --layout auto: dense bits up to kDenseLimitBytes (small grids voxelize fastest dense: no coarse pass, and
// the host writes straight into the result), bricks beyond, or when the dense bits exceed what the device
// can allocate.
constexpr uint64_t kDenseLimitBytes = uint64_t(512) << 20;

bool choose_sparse(const std::string& layout, const GridSpec& grid, const VoxelizeOptions& options,
                   const ClRuntime& cl) {
  if (layout == "dense") return false;
  if (layout == "sparse") {
    SparseVoxelizer::validate(options);
    return true;
  }
  const uint64_t dense = dense_occupancy_bytes(grid.dims);
  if (dense <= kDenseLimitBytes && dense <= cl.device().max_allocation) return false;
  try {
    SparseVoxelizer::validate(options);
  } catch (const Error&) {
    return false;  // solid fill, slicemap, lists: dense, which says so itself if the grid does not fit
  }
  return true;
}

struct Phases {
  double load_ms = 0.0;      // reading the input, validating it, fitting the grid
  double wait_ms = 0.0;      // waiting for the runtime and programs after the load
  double runtime_ms = 0.0;   // opening the OpenCL device (in the background)
  double programs_ms = 0.0;  // building or loading the programs (in the background)
  double write_ms = 0.0;
  double process_ms = 0.0;  // from the start of the command to the report
};

nlohmann::json make_report(const VoxelizeArgs& args, const ClRuntime& cl, const GridSpec& grid,
                           const VoxelizeOptions& options, const VoxelizeStats& stats, const Phases& phases,
                           const ChannelSet& channels, const std::optional<SparseStats>& sparse,
                           uint64_t host_bytes) {
  nlohmann::json stages = nlohmann::json::object();
  for (const auto& [name, ms] : stats.stage_ms) stages[name] = ms;
  nlohmann::json report = {
      {"input", args.input.empty() ? "default scene" : args.input},
      {"device", cl.device().label()},
      {"driver", cl.device().driver_version},
      {"method", method_info(options.method).name},
      {"mode", options.method == VoxelizeMethod::kSlicemap ? "center" : raster_mode_name(options.mode)},
      {"channels", channels.to_string()},
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
      {"layout", sparse ? "sparse" : "dense"},
      {"host_bytes", host_bytes},
      {"ms",
       {{"upload", stats.upload_ms},
        {"kernels", stats.kernels_ms},
        {"readback", stats.readback_ms},
        {"total", stats.total_ms()},
        {"wall", stats.wall_ms},
        {"stages", stages},
        {"load", phases.load_ms},
        {"runtime", phases.runtime_ms},
        {"programs", phases.programs_ms},
        {"wait", phases.wait_ms},
        {"write", phases.write_ms},
        {"process", phases.process_ms}}},
  };
  if (sparse)
    report["sparse"] = {
        {"brick", kBrickEdge},
        {"slabs", sparse->slabs},
        {"bricks_marked", sparse->bricks_marked},
        {"bricks", sparse->bricks_kept},
        {"memory_budget", sparse->memory_budget},
        {"peak_device_bytes", sparse->peak_device_bytes},
        {"peak_grid_bytes", sparse->peak_grid_bytes},
        {"grid_bytes_per_voxel",
         stats.voxels_set ? double(sparse->peak_grid_bytes) / double(stats.voxels_set) : 0.0},
        {"device_bytes_per_voxel",
         stats.voxels_set ? double(sparse->peak_device_bytes) / double(stats.voxels_set) : 0.0},
        {"host_bytes_per_voxel", stats.voxels_set ? double(host_bytes) / double(stats.voxels_set) : 0.0}};
  if (options.method == VoxelizeMethod::kSlicemap) report["slicing"] = slicemap_slicing_name(options.slicing);
  if (options.solid)
    report["solid"] = {{"mode", solid_mode_name(*options.solid)},
                       {"inside_voxels", stats.inside_voxels},
                       {"questionable_columns", stats.questionable_columns},
                       {"repair_iterations", stats.repair_iterations},
                       {"flood_iterations", stats.flood_iterations}};
  return report;
}

// The resolutions --error-target searches, and the fixed grid its saving is measured against.
constexpr uint32_t kTargetLowest = 16, kTargetHighest = 1024, kTargetCompare = 512;
constexpr uint32_t kTargetSamples = 50000;  // surface points and set voxels per measurement

// --error-target: the smallest resolution whose surface voxelization (the user's method and rule, occupancy
// only) lies within `target` of the triangles (voxel_surface_error: two-sided mean surface distance over
// kTargetSamples surface points and up to as many set voxels, relative to the longest side), each candidate
// voxelized and measured in full on the host.
ResolutionChoice search_surface_resolution(Voxelizer& voxelizer, const TriangleSoup& soup,
                                           const Bounds& bounds, const GridRequest& request,
                                           const VoxelizeOptions& options, double target, bool tty) {
  VoxelizeOptions probe = options;
  probe.solid.reset();
  probe.channels = ChannelSet::parse("occ");
  probe.progress = nullptr;
  return choose_resolution(target, kTargetLowest, kTargetHighest, [&](uint32_t r) {
    GridRequest q = request;
    q.resolution = r;
    q.dims.reset();
    const GridSpec g = fit_grid(bounds, q, soup.anchor);
    const double e =
        voxel_surface_error(voxelizer.run(soup, g, probe, nullptr, &bounds), g, soup, kTargetSamples)
            .chamfer();
    if (tty) fmt::print(stderr, "\rerror target: res {} -> {:.5f}{:<20}", r, e, "");
    return e;
  });
}

int run_voxelize(const VoxelizeArgs& args) {
  const auto process_start = Clock::now();
  if (args.res && !args.dims.empty()) fail("--res and --dims are exclusive; give one");
  if (args.error_target && (args.res || !args.dims.empty()))
    fail("--error-target chooses the resolution; leave out --res and --dims");
  if (!args.report.empty()) check_output_path(args.report);
  if (args.layout != "auto" && args.layout != "dense" && args.layout != "sparse")
    fail("--layout '{}': expected auto, dense or sparse", args.layout);
  const uint64_t memory_budget = args.memory_budget.empty() ? 0 : parse_memory_budget(args.memory_budget);
  if (args.layout == "sparse" && args.error_target)
    fail("--error-target searches dense grids: leave out --layout sparse");
  const std::filesystem::path viewer = args.view ? find_viewer(args.output) : std::filesystem::path();
  VoxelizeOptions options = voxelize_options(args);
  const bool tty = isatty(fileno(stderr)) && !args.quiet;
  if (tty)
    options.progress = [](const std::string& stage) { fmt::print(stderr, "\rvoxelizing: {:<12}", stage); };

  // A missing or unreadable input fails at once, not after the device and programs are ready (the
  // background thread is joined before any error leaves this function).
  if (!args.input.empty()) {
    std::error_code ec;
    if (!std::filesystem::exists(args.input, ec)) fail("{}: no such file", args.input);
    if (!std::ifstream(args.input, std::ios::binary))
      fail("{}: cannot open the file for reading", args.input);
  }
  // The device and the programs in the background while the input is read.
  auto background = prepare_in_background<Voxelizer>(args.device, options);
  Phases phases;
  auto load_start = Clock::now();
  if (tty) fmt::print(stderr, "\rreading {}...", args.input.empty() ? "the default scene" : args.input);
  Scene scene = args.input.empty() ? default_scene() : load_input(args.input);
  const char* cr = tty ? "\r" : "";
  for (const MeshInstance& m : scene.meshes)
    for (const std::string& w : m.warnings) fmt::print(stderr, "{}voxr: warning: {}\n", cr, w);
  for (const std::string& w : scene.warnings) fmt::print(stderr, "{}voxr: warning: {}\n", cr, w);
  TriangleSoup soup = take_scene_triangles(scene);
  const size_t degenerate = validate_soup(soup, scene.source);
  if (options.channels.has(Channel::kColor) && soup.colors.empty())
    fmt::print(stderr, "{}voxr: warning: {} has no colours; the color channel is white\n", cr, scene.source);
  const Bounds bounds = soup.bounds();

  GridRequest request = scene.grid;
  if (args.res) {
    request.resolution = args.res;
    request.dims.reset();
  }
  if (!args.dims.empty()) request.dims = parse_dims(args.dims, "--dims");
  if (!args.bounds.empty()) request.bounds = parse_bounds(args.bounds, "--bounds");
  if (args.error_target) request.dims.reset();  // a scene's "grid" dims give way to the search
  fit_request_to_format(request, args.output);
  GridSpec grid = fit_grid(bounds, request, soup.anchor);
  // With --error-target the grid is known after the search: folder and format are checked now, the size the
  // format holds after it.
  if (!args.output.empty()) check_volume_output(args.output, args.error_target ? glm::uvec3(1) : grid.dims);

  bool refit = false;
  if (options.solid) {
    // Closure is judged on welded positions; a triangle listed twice would flip every column parity
    // through it, and the winding-number definition of inside ignores the copy, so copies go.
    MeshTopology topology = mesh_topology(soup);
    if (topology.duplicates > 0) {
      drop_duplicate_triangles(soup);
      fmt::print(
          stderr,
          "{}voxr: warning: {}: {} triangles repeat an earlier triangle exactly (first: triangle {}); the "
          "copies were dropped\n",
          cr, scene.source, topology.duplicates, topology.first_duplicate);
    }
    if (!topology.closed() && (options.solid == SolidMode::kParity || options.solid == SolidMode::kXor)) {
      // Column parity needs a closed surface. Late filling repairs the columns that cross a hole from their
      // neighbours: on the holed test meshes it stays within a few voxels of the winding-number reference,
      // where flood fill loses the interior once a hole is wider than a voxel (bench/results/solid-*).
      fmt::print(stderr,
                 "{}voxr: warning: {} is not closed ({}); --solid {} would leak through the holes, "
                 "using --solid late\n",
                 cr, scene.source, topology.describe(soup.anchor), args.solid);
      options.solid = SolidMode::kLate;
      refit = true;
    }
  }
  phases.load_ms = ms_since(load_start);

  const auto wait_start = Clock::now();
  PreparedRuntime<Voxelizer> prepared = background.get();
  phases.wait_ms = ms_since(wait_start);
  phases.runtime_ms = prepared.runtime_ms;
  phases.programs_ms = prepared.programs_ms;
  ClRuntime& cl = *prepared.cl;
  Voxelizer& voxelizer = *prepared.engine;
  if (refit) voxelizer.prepare(options);

  std::optional<ResolutionChoice> choice;
  const auto search_start = Clock::now();
  if (args.error_target) {
    choice = search_surface_resolution(voxelizer, soup, bounds, request, options, *args.error_target, tty);
    request.resolution = choice->resolution;
    request.dims.reset();
    fit_request_to_format(request, args.output);
    grid = fit_grid(bounds, request, soup.anchor);
    if (!args.output.empty()) check_volume_output(args.output, grid.dims);
  }
  const double search_ms = args.error_target ? ms_since(search_start) : 0.0;

  VoxelizeStats stats;
  const bool sparse_layout = choose_sparse(args.layout, grid, options, cl);
  std::optional<SparseStats> sparse_stats;
  SparseVoxelGrid sparse_result;
  VoxelGrid result;
  if (sparse_layout) {
    SparseVoxelizer sparse(cl);
    sparse_stats.emplace();
    sparse_result = sparse.run(soup, grid, options, memory_budget, &stats, &*sparse_stats, &bounds);
  } else {
    result = voxelizer.run(soup, grid, options, &stats, &bounds);
  }
  const ChannelSet result_channels = sparse_layout ? sparse_result.channels : result.channels;
  const uint64_t host_bytes = sparse_layout ? sparse_result.memory_bytes() : result.memory_bytes();
  if (!sparse_layout && memory_budget)
    fmt::print(
        stderr,
        "voxr: warning: --memory-budget applies to the sparse layout; the {} x {} x {} grid ran dense\n",
        grid.dims.x, grid.dims.y, grid.dims.z);
  // The saving is measured: the same job on the fixed grid it replaces.
  VoxelizeStats fixed;
  GridSpec fixed_grid;
  if (choice) {
    GridRequest q = request;
    q.resolution = kTargetCompare;
    q.dims.reset();
    fit_request_to_format(q, args.output);
    fixed_grid = fit_grid(bounds, q, soup.anchor);
    voxelizer.run(soup, fixed_grid, options, &fixed, &bounds);
  }
  if (tty) fmt::print(stderr, "\r{:<40}\r", "");
  // An empty volume is written (it is the right answer for a grid beside the mesh), never silently.
  if (stats.voxels_set == 0 && stats.inside_voxels == 0)
    fmt::print(stderr, "voxr: warning: no voxel of the {} x {} x {} grid touches {}{}\n", grid.dims.x,
               grid.dims.y, grid.dims.z, scene.source, args.bounds.empty() ? "" : " (check --bounds)");

  std::vector<std::filesystem::path> written;
  if (!args.output.empty()) {
    const auto write_start = Clock::now();
    if (tty) fmt::print(stderr, "writing {}...", args.output);
    written = sparse_layout ? write_volume(sparse_result, args.output) : write_volume(result, args.output);
    if (tty) fmt::print(stderr, "\r{:<60}\r", "");
    phases.write_ms = ms_since(write_start);
  }
  phases.process_ms = ms_since(process_start);
  nlohmann::json report =
      make_report(args, cl, grid, options, stats, phases, result_channels, sparse_stats, host_bytes);
  if (choice) {
    nlohmann::json trials = nlohmann::json::array();
    for (const ResolutionTrial& t : choice->trials)
      trials.push_back({{"res", t.resolution}, {"error", t.error}});
    report["error_target"] = {
        {"target", *args.error_target},
        {"measure", "voxel surface error: two-sided mean surface distance / longest side (chamfer)"},
        {"met", choice->met},
        {"res", choice->resolution},
        {"error", choice->error},
        {"trials", trials},
        {"search_ms", search_ms},
        {"fixed",
         {{"res", kTargetCompare},
          {"dims", {fixed_grid.dims.x, fixed_grid.dims.y, fixed_grid.dims.z}},
          {"device_bytes", fixed.device_bytes},
          {"wall_ms", fixed.wall_ms}}}};
  }
  if (!args.report.empty()) {
    write_file_atomically(args.report, report.dump(2) + "\n");
  }
  if (!args.quiet) {
    fmt::print("input      {}\n", scene.source);
    fmt::print("device     {}\n", cl.device().label());
    fmt::print("triangles  {} ({} degenerate, {} split", stats.triangles, degenerate, stats.triangles_split);
    if (options.method == VoxelizeMethod::kHybrid)
      fmt::print(", {} direct, {} by slice duplication", stats.direct_triangles,
                 stats.triangles - stats.direct_triangles);
    fmt::print(")\n");
    const std::string rule =
        options.method == VoxelizeMethod::kSlicemap
            ? fmt::format("slicemap {}", slicemap_slicing_name(options.slicing))
            : fmt::format("{} {}", method_info(options.method).name, raster_mode_name(options.mode));
    fmt::print("grid       {} x {} x {}, voxel {:.6g}, {}{}, channels {}\n", grid.dims.x, grid.dims.y,
               grid.dims.z, grid.voxel_size, rule,
               options.solid ? fmt::format(", solid {}", solid_mode_name(*options.solid)) : "",
               result_channels.to_string());
    fmt::print("copies     {} in {} batch(es), {} raster work items\n", stats.copies, stats.batches,
               stats.work_items);
    fmt::print("voxels set {} ({:.3f}% of {})\n", stats.voxels_set,
               100.0 * double(stats.voxels_set) / double(grid.voxel_count()), grid.voxel_count());
    if (options.solid)
      fmt::print("inside     {} voxels ({} questionable columns, {} flood rounds)\n", stats.inside_voxels,
                 stats.questionable_columns, stats.flood_iterations);
    if (sparse_stats)
      fmt::print(
          "layout     sparse: {} bricks of 8^3 ({} marked), {} slab(s) under a {:.0f} MiB budget; on the "
          "device at "
          "most {:.1f} MiB, of which grid {:.1f} MiB ({:.2f} B per set voxel); {:.1f} MiB on the host "
          "({:.2f} B per "
          "set voxel)\n",
          sparse_stats->bricks_kept, sparse_stats->bricks_marked, sparse_stats->slabs,
          double(sparse_stats->memory_budget) / (1 << 20), double(stats.device_bytes) / (1 << 20),
          double(sparse_stats->peak_grid_bytes) / (1 << 20),
          double(sparse_stats->peak_grid_bytes) / double(std::max<uint64_t>(stats.voxels_set, 1)),
          double(host_bytes) / (1 << 20),
          double(host_bytes) / double(std::max<uint64_t>(stats.voxels_set, 1)));
    else
      fmt::print("memory     {:.1f} MiB on the device (dense layout)\n",
                 double(stats.device_bytes) / (1 << 20));
    if (choice) {
      std::string trials;
      for (const ResolutionTrial& t : choice->trials)
        trials += fmt::format("{}{} -> {:.5f}", trials.empty() ? "" : ", ", t.resolution, t.error);
      fmt::print(
          "target     surface error {:.5f} {} at res {} (error {:.5f}; measured {}; search {:.0f} ms)\n",
          *args.error_target, choice->met ? "met" : "NOT met (the least error measured)", choice->resolution,
          choice->error, trials, search_ms);
      fmt::print(
          "vs res {}  {:.1f} MiB and {:.2f} ms wall on {} x {} x {}: saving {:.1f} MiB ({:.0f}%) and {:.2f} "
          "ms\n",
          kTargetCompare, double(fixed.device_bytes) / (1 << 20), fixed.wall_ms, fixed_grid.dims.x,
          fixed_grid.dims.y, fixed_grid.dims.z,
          (double(fixed.device_bytes) - double(stats.device_bytes)) / (1 << 20),
          100.0 * (1.0 - double(stats.device_bytes) / double(std::max<uint64_t>(fixed.device_bytes, 1))),
          fixed.wall_ms - stats.wall_ms);
    }
    fmt::print(
        "time       upload {:.2f} ms + kernels {:.2f} ms + readback {:.2f} ms = {:.2f} ms (wall {:.2f} ms)\n",
        stats.upload_ms, stats.kernels_ms, stats.readback_ms, stats.total_ms(), stats.wall_ms);
    std::string stages;
    for (const auto& [name, ms] : stats.stage_ms)
      stages += fmt::format("{}{} {:.2f}", stages.empty() ? "" : ", ", name, ms);
    fmt::print("stages ms  {}\n", stages);
    fmt::print(
        "process ms load {:.1f}, device {:.1f} + programs {:.1f} (waited {:.1f}), write {:.1f}, all {:.1f}\n",
        phases.load_ms, phases.runtime_ms, phases.programs_ms, phases.wait_ms, phases.write_ms,
        phases.process_ms);
    for (const auto& path : written) fmt::print("wrote      {}\n", path.string());
  }
  if (args.profile) fmt::print("\n{}", cl.profiler().table());
  return args.view ? run_program({viewer.string(), args.output}) : 0;
}

}  // namespace

Command add_voxelize(CLI::App& app) {
  auto args = std::make_shared<VoxelizeArgs>();
  CLI::App* sub = app.add_subcommand("voxelize", "Voxelize a mesh or a scene (.json)");
  sub->add_option("input", args->input,
                  "mesh (" + mesh_extensions() + ") or scene file; omitted: the built-in default scene");
  sub->add_option("-o,--output", args->output,
                  "output volume: .vdb (OpenVDB, sparse), .npz (sparse voxel list), .nrrd, .vti, .binvox "
                  "(cubic: --res N gives N^3), .vox (<=256)");
  add_grid_option(*sub, "--res", GridKind::kVoxel, args->res)->default_str("256, or the scene's grid");
  sub->add_option("--dims", args->dims, "exact grid dimensions X,Y,Z");
  sub->add_option(
      "--bounds", args->bounds,
      "world box x0,y0,z0,x1,y1,z1, used exactly (default: the scene bounds with a quarter-voxel margin)");
  std::string methods;
  for (const MethodInfo& info : kMethods)
    methods += fmt::format("{}{} ({})", methods.empty() ? "" : "; ", info.name, info.summary);
  sub->add_option("--method", args->method, methods)->capture_default_str();
  sub->add_option("--solid", args->solid,
                  "also fill the interior (inside channel: voxels whose centre is inside): xor, late, parity "
                  "(exact on closed meshes) or flood (robust to holes)");
  sub->add_option("--slicing", args->slicing,
                  "slicemap slicing: uniform (default) or local (scene-fitted per column)");
  sub->add_option(
      "--mode", args->mode,
      "conservative (default: every voxel the triangle touches, a guaranteed superset) or center (the "
      "papers' pixel-centre rule)");
  sub->add_option("--channels", args->channels,
                  "comma list of occ,count,normal,material,color (inside comes with --solid)")
      ->capture_default_str();
  add_device_option(*sub, args->device);
  add_report_options(*sub, args->report, args->profile, args->quiet, "counts, grid, memory and times");
  sub->add_option("--error-target", args->error_target,
                  "choose the smallest resolution (16..1024) whose surface lies within E of the triangles: "
                  "two-sided mean surface distance over the longest side, measured per candidate; reports "
                  "the saving against --res 512")
      ->check(CLI::Range(0.0, 1.0));
  sub->add_option(
         "--layout", args->layout,
         "dense (one bit per voxel of the grid), sparse (8^3 bricks where the surface is: memory grows "
         "with the surface, for 2048^3 and beyond) or auto (sparse once the dense bits pass 512 MiB or "
         "the device's largest allocation)")
      ->capture_default_str();
  sub->add_option("--memory-budget", args->memory_budget,
                  "device memory a sparse run may use, e.g. 512M or 4G (default: a quarter of the device's "
                  "memory, at most twice its largest allocation); larger grids are voxelized in slabs");
  sub->add_option("--rows-per-copy", args->rows_per_copy, "rows one raster work item walks (tuning)")
      ->check(CLI::Range(1u, 4096u))
      ->capture_default_str();
  sub->add_flag("--view", args->view, "open the written volume (.vti, .nrrd, .vdb) in voxr-view");
  return {sub, [args] { return run_voxelize(*args); }};
}

}  // namespace voxr::cli
