// voxr voxelize INPUT -o OUT: mesh or scene -> voxel grid (any method, rule, channels and solid fill, on one
// upload), written by extension, with a summary (and optional JSON report) of counts, memory and times.
//
// A fresh process pays only what it must: the OpenCL runtime is opened and every program the run needs is
// built (or loaded from the program cache) on a second thread while the mesh is read, and the timed
// voxelization starts after both.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>
#include <optional>

#include "cl/cl_runtime.h"
#include "cl/prepared_runtime.h"
#include "cli/commands.h"
#include "cli/option_groups.h"
#include "cli/parse_args.h"
#include "cli/process.h"
#include "cli/progress_display.h"
#include "core/default_scene.h"
#include "core/mesh_loader.h"
#include "core/resolution_search.h"
#include "core/scene.h"
#include "io/atomic_file.h"
#include "io/volume_writer.h"
#include "metrics/voxel_surface_error.h"
#include "util/clock.h"
#include "voxelize/voxelize_job.h"

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
  bool progress = false;  // --progress
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
  return make_voxelize_options(
      {args.method, args.mode, args.slicing, args.channels, args.solid, args.rows_per_copy});
}

struct Phases {
  double load_ms = 0.0;      // reading the input, validating it, fitting the grid
  double wait_ms = 0.0;      // waiting for the runtime and programs after the load
  double runtime_ms = 0.0;   // opening the OpenCL device (in the background)
  double programs_ms = 0.0;  // building or loading the programs (in the background)
  double write_ms = 0.0;
  double process_ms = 0.0;  // from the start of the command to the report
};

// The job's report with the process's phases added to its times.
nlohmann::json make_report(const VoxelizeArgs& args, const ClRuntime& cl, const GridSpec& grid,
                           const VoxelizeOptions& options, const VoxelizeResult& result,
                           const Phases& phases) {
  nlohmann::json report =
      voxelize_report(args.input.empty() ? "default scene" : args.input, cl, grid, options, result);
  nlohmann::json& ms = report["ms"];
  ms["load"] = phases.load_ms;
  ms["runtime"] = phases.runtime_ms;
  ms["programs"] = phases.programs_ms;
  ms["wait"] = phases.wait_ms;
  ms["write"] = phases.write_ms;
  ms["process"] = phases.process_ms;
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
                                           const VoxelizeOptions& options, double target,
                                           const ProgressDisplay& progress) {
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
    progress.show(fmt::format("error target: res {} -> {:.5f}", r, e));
    return e;
  });
}

int run_voxelize(const VoxelizeArgs& args) {
  const auto process_start = Clock::now();
  if (args.res && !args.dims.empty()) fail("--res and --dims are exclusive; give one");
  if (args.error_target && (args.res || !args.dims.empty()))
    fail("--error-target chooses the resolution; leave out --res and --dims");
  if (!args.report.empty()) check_output_path(args.report);
  const GridLayout layout = parse_grid_layout(args.layout, "--layout");
  const uint64_t memory_budget =
      args.memory_budget.empty() ? 0 : parse_memory_size(args.memory_budget, "--memory-budget");
  if (layout == GridLayout::kSparse && args.error_target)
    fail("--error-target searches dense grids: leave out --layout sparse");
  const std::filesystem::path viewer = args.view ? find_viewer(args.output) : std::filesystem::path();
  VoxelizeOptions options = voxelize_options(args);
  const ProgressDisplay progress(args.progress, args.quiet);
  if (progress.active())
    options.progress = [&progress](const std::string& stage) { progress.show("voxelizing: " + stage); };

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
  progress.show(fmt::format("reading {}...", args.input.empty() ? "the default scene" : args.input));
  VoxelizeInput input =
      prepare_voxelize_input(args.input.empty() ? default_scene() : load_input(args.input), options);
  for (const std::string& w : input.warnings)
    fmt::print(stderr, "{}voxr: warning: {}\n", progress.line_start(), w);
  GridChoice choice_of_grid{args.res, std::nullopt, std::nullopt};
  if (!args.dims.empty()) choice_of_grid.dims = parse_dims(args.dims, "--dims");
  if (!args.bounds.empty()) choice_of_grid.bounds = parse_bounds(args.bounds, "--bounds");
  GridRequest request = choose_grid_request(input.request, choice_of_grid);
  if (args.error_target) request.dims.reset();  // a scene's "grid" dims give way to the search
  fit_request_to_format(request, args.output);
  GridSpec grid = fit_grid(input.bounds, request, input.soup.anchor);
  // With --error-target the grid is known after the search: folder and format are checked now, the size the
  // format holds after it.
  if (!args.output.empty()) check_volume_output(args.output, args.error_target ? glm::uvec3(1) : grid.dims);
  phases.load_ms = ms_since(load_start);

  const auto wait_start = Clock::now();
  PreparedRuntime<Voxelizer> prepared = background.get();
  phases.wait_ms = ms_since(wait_start);
  phases.runtime_ms = prepared.runtime_ms;
  phases.programs_ms = prepared.programs_ms;
  ClRuntime& cl = *prepared.cl;
  Voxelizer& voxelizer = *prepared.engine;
  if (input.solid_switched) voxelizer.prepare(options);

  std::optional<ResolutionChoice> choice;
  const auto search_start = Clock::now();
  if (args.error_target) {
    choice = search_surface_resolution(voxelizer, input.soup, input.bounds, request, options,
                                       *args.error_target, progress);
    request.resolution = choice->resolution;
    request.dims.reset();
    fit_request_to_format(request, args.output);
    grid = fit_grid(input.bounds, request, input.soup.anchor);
    if (!args.output.empty()) check_volume_output(args.output, grid.dims);
  }
  const double search_ms = args.error_target ? ms_since(search_start) : 0.0;

  std::unique_ptr<SparseVoxelizer> bricks;
  const VoxelizeResult result = run_voxelize_job(cl, voxelizer, bricks, input, grid, options, layout,
                                                 memory_budget, !args.bounds.empty());
  const VoxelizeStats& stats = result.stats;
  // The saving is measured: the same job on the fixed grid it replaces.
  VoxelizeStats fixed;
  GridSpec fixed_grid;
  if (choice) {
    GridRequest q = request;
    q.resolution = kTargetCompare;
    q.dims.reset();
    fit_request_to_format(q, args.output);
    fixed_grid = fit_grid(input.bounds, q, input.soup.anchor);
    voxelizer.run(input.soup, fixed_grid, options, &fixed, &input.bounds);
  }
  progress.clear();
  for (const std::string& w : result.warnings) fmt::print(stderr, "voxr: warning: {}\n", w);

  std::vector<std::filesystem::path> written;
  if (!args.output.empty()) {
    const auto write_start = Clock::now();
    progress.show(fmt::format("writing {}...", args.output));
    written =
        result.sparse ? write_volume(result.bricks, args.output) : write_volume(result.dense, args.output);
    progress.clear();
    phases.write_ms = ms_since(write_start);
  }
  phases.process_ms = ms_since(process_start);
  nlohmann::json report = make_report(args, cl, grid, options, result, phases);
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
    fmt::print("input      {}\n", input.source);
    fmt::print("device     {}\n", cl.device().label());
    fmt::print("triangles  {} ({} degenerate, {} split", stats.triangles, input.degenerate,
               stats.triangles_split);
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
               result.channels().to_string());
    fmt::print("copies     {} in {} batch(es), {} raster work items\n", stats.copies, stats.batches,
               stats.work_items);
    fmt::print("voxels set {} ({:.3f}% of {})\n", stats.voxels_set,
               100.0 * double(stats.voxels_set) / double(grid.voxel_count()), grid.voxel_count());
    if (options.solid)
      fmt::print("inside     {} voxels ({} questionable columns, {} flood rounds)\n", stats.inside_voxels,
                 stats.questionable_columns, stats.flood_iterations);
    if (const std::optional<SparseStats>& sparse_stats = result.sparse_stats)
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
          double(result.host_bytes()) / (1 << 20),
          double(result.host_bytes()) / double(std::max<uint64_t>(stats.voxels_set, 1)));
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
  sub->add_flag("--progress", args->progress,
                "show each step on stderr even with -q or when stderr is not a terminal (one line per step, "
                "with the seconds since the start)");
  sub->add_flag("--view", args->view, "open the written volume (.vti, .nrrd, .vdb) in voxr-view");
  return {sub, [args] { return run_voxelize(*args); }};
}

}  // namespace voxr::cli
