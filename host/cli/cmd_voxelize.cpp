// voxr voxelize INPUT -o OUT: mesh or scene -> voxel grid with the slice voxelizer, written by extension,
// with a summary (and optional JSON report) of counts, memory and per-stage times.
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "cl/cl_runtime.h"
#include "cli/commands.h"
#include "cli/parse_args.h"
#include "core/default_scene.h"
#include "core/mesh_topology.h"
#include "core/scene.h"
#include "io/volume_writer.h"
#include "voxelize/slice_voxelizer.h"
#include "voxelize/slicemap_voxelizer.h"
#include "voxelize/solid_voxelizer.h"

namespace voxr::cli {

namespace {

struct VoxelizeArgs {
  std::string input;  // empty: the built-in default scene
  std::string output;
  uint32_t res = 0;
  std::string dims, bounds;
  std::string method = "slice";
  std::string mode;     // empty: conservative (slice, grid)
  std::string slicing;  // empty: uniform (slicemap)
  std::string solid;    // empty: surface only
  std::string channels = "occ";
  std::string device;
  std::string report;
  uint32_t rows_per_copy = 4;
  bool profile = false;
  bool quiet = false;
  bool view = false;
};

// --view: voxr-view is this executable's neighbour (CMake puts both in the build folder).
std::filesystem::path find_viewer(const std::string& output) {
  if (output.empty()) fail("--view needs -o OUT: the viewer opens the written volume");
  std::string ext = std::filesystem::path(output).extension().string();
  for (char& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  if (ext != ".vti" && ext != ".nrrd")
    fail("--view: voxr-view reads .vti and .nrrd outputs, not '{}'", output);
  std::error_code ec;
  const std::filesystem::path viewer =
      std::filesystem::read_symlink("/proc/self/exe", ec).parent_path() / "voxr-view";
  if (ec || !std::filesystem::exists(viewer))
    fail("--view: {} not found (configure with -DVOXR_BUILD_VIEWER=ON and build it)", viewer.string());
  return viewer;
}

// Runs voxr-view on `volume` and returns its exit code.
int run_viewer(const std::filesystem::path& viewer, const std::string& volume) {
  std::fflush(stdout);
  std::string exe = viewer.string(), file = volume;
  char* argv[] = {exe.data(), file.data(), nullptr};
  pid_t pid = 0;
  if (posix_spawn(&pid, exe.c_str(), nullptr, nullptr, argv, environ) != 0)
    fail("--view: cannot start {}", exe);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

nlohmann::json make_report(const VoxelizeArgs& args, const ClRuntime& cl, const GridSpec& grid,
                           const VoxelizeOptions& options, const VoxelizeStats& stats) {
  nlohmann::json stages = nlohmann::json::object();
  for (const auto& [name, ms] : stats.stage_ms) stages[name] = ms;
  return {
      {"input", args.input.empty() ? "default scene" : args.input},
      {"device", cl.device().label()},
      {"driver", cl.device().driver_version},
      {"method", args.method},
      {"mode", args.method == "slicemap" ? "center" : raster_mode_name(options.mode)},
      {"channels", options.channels.to_string()},
      {"triangles", stats.triangles},
      {"triangles_split", stats.triangles_split},
      {"dims", {grid.dims.x, grid.dims.y, grid.dims.z}},
      {"voxel_size", grid.voxel_size},
      {"origin", {grid.origin.x, grid.origin.y, grid.origin.z}},
      {"copies", stats.copies},
      {"batches", stats.batches},
      {"voxels_set", stats.voxels_set},
      {"device_bytes", stats.device_bytes},
      {"ms",
       {{"upload", stats.upload_ms},
        {"kernels", stats.kernels_ms},
        {"readback", stats.readback_ms},
        {"total", stats.total_ms()},
        {"wall", stats.wall_ms},
        {"stages", stages}}},
  };
}

int run_voxelize(const VoxelizeArgs& args) {
  if (args.res && !args.dims.empty()) fail("--res and --dims are exclusive; give one");
  if (!args.report.empty()) check_output_path(args.report);
  const std::filesystem::path viewer = args.view ? find_viewer(args.output) : std::filesystem::path();
  const Scene scene = args.input.empty() ? default_scene() : load_input(args.input);
  const TriangleSoup soup = scene_triangles(scene);
  const size_t degenerate = validate_soup(soup, scene.source);

  GridRequest request = scene.grid;
  if (args.res) {
    request.resolution = args.res;
    request.dims.reset();
  }
  if (!args.dims.empty()) request.dims = parse_dims(args.dims, "--dims");
  if (!args.bounds.empty()) request.bounds = parse_bounds(args.bounds, "--bounds");
  const GridSpec grid = fit_grid(soup.bounds(), request);
  if (!args.output.empty()) check_volume_output(args.output, grid.dims);

  VoxelizeOptions options;
  const bool slicemap = args.method == "slicemap";
  if (args.method == "grid") {
    options.method = VoxelizeMethod::kGrid;
  } else if (!slicemap && args.method != "slice") {
    fail("unknown --method '{}' (methods: slice, grid, slicemap)", args.method);
  }
  if (slicemap && !args.mode.empty())
    fail("--mode does not apply to --method slicemap (it samples column centres)");
  if (!slicemap && !args.slicing.empty()) fail("--slicing applies to --method slicemap only");
  const SlicemapSlicing slicing = parse_slicemap_slicing(args.slicing.empty() ? "uniform" : args.slicing);
  options.mode = parse_raster_mode(args.mode.empty() ? "conservative" : args.mode);
  options.channels = ChannelSet::parse(args.channels);
  if (slicemap && options.channels.attributes())
    fail("--method slicemap is binary: it produces the occ channel only (got --channels {})", args.channels);
  if (options.channels.has(Channel::kInside) && args.solid.empty())
    fail("the inside channel comes from solid voxelization: add --solid xor|late|parity|flood");
  std::optional<SolidMode> solid;
  if (!args.solid.empty()) {
    solid = parse_solid_mode(args.solid);
    if (args.method != "slice" || options.channels.attributes())
      fail("--solid produces the occ and inside channels with its own kernels: drop --method and --channels");
    const MeshTopology topology = mesh_topology(soup);
    if ((*solid == SolidMode::kParity || *solid == SolidMode::kXor) && !topology.closed()) {
      // Column parity needs a closed surface. Late filling repairs the columns that cross a hole from their
      // neighbours: on the holed test meshes it stays within a few voxels of the winding-number reference,
      // where flood fill loses the interior once a hole is wider than a voxel (bench/results/solid-*).
      fmt::print(
          stderr,
          "voxr: warning: {} is not closed ({} boundary and {} non-manifold edges); --solid {} would leak "
          "through the holes, using --solid late\n",
          scene.source, topology.boundary, topology.nonmanifold, args.solid);
      solid = SolidMode::kLate;
    }
  }
  options.rows_per_copy = args.rows_per_copy;
  const bool tty = isatty(fileno(stderr)) && !args.quiet;
  if (tty)
    options.progress = [](const std::string& stage) { fmt::print(stderr, "\rvoxelizing: {:<12}", stage); };

  ClRuntime cl(args.device);
  VoxelizeStats stats;
  SolidStats solid_stats;
  const VoxelGrid result = solid      ? SolidVoxelizer(cl).run(soup, grid, *solid, &solid_stats)
                           : slicemap ? SlicemapVoxelizer(cl).run(soup, grid, slicing, &stats)
                                      : SliceVoxelizer(cl).run(soup, grid, options, &stats);
  if (solid) {
    stats.triangles = soup.triangle_count();
    stats.voxels_set = result.voxels_set;
    stats.kernels_ms = solid_stats.kernels_ms;
    stats.stage_ms = solid_stats.stage_ms;
  }
  if (tty) fmt::print(stderr, "\r{:<32}\r", "");

  std::vector<std::filesystem::path> written;
  if (!args.output.empty()) {
    if (tty) fmt::print(stderr, "writing {}...", args.output);
    written = write_volume(result, args.output);
    if (tty) fmt::print(stderr, "\r{:<60}\r", "");
  }
  nlohmann::json report = make_report(args, cl, grid, options, stats);
  report["channels"] = result.channels.to_string();
  if (solid) {
    report["solid"] = {{"mode", solid_mode_name(*solid)},
                       {"inside_voxels", solid_stats.inside_voxels},
                       {"questionable_columns", solid_stats.questionable_columns},
                       {"flood_iterations", solid_stats.flood_iterations}};
  }
  if (!args.report.empty()) {
    std::ofstream out(args.report);
    out << report.dump(2) << "\n";
    if (!out) fail("{}: cannot write the report", args.report);
  }
  if (!args.quiet) {
    fmt::print("input      {}\n", scene.source);
    fmt::print("device     {}\n", cl.device().label());
    fmt::print("triangles  {} ({} degenerate, {} split)\n", stats.triangles, degenerate,
               stats.triangles_split);
    const std::string rule = solid      ? fmt::format("solid {}", solid_mode_name(*solid))
                             : slicemap ? fmt::format("slicemap {}", slicemap_slicing_name(slicing))
                                        : fmt::format("{} {}", args.method, raster_mode_name(options.mode));
    fmt::print("grid       {} x {} x {}, voxel {:.6g}, {}, channels {}\n", grid.dims.x, grid.dims.y,
               grid.dims.z, grid.voxel_size, rule, result.channels.to_string());
    if (solid) {
      fmt::print("inside     {} voxels ({} questionable columns, {} flood rounds)\n",
                 solid_stats.inside_voxels, solid_stats.questionable_columns, solid_stats.flood_iterations);
    } else {
      fmt::print("copies     {} in {} batch(es), {} raster work items\n", stats.copies, stats.batches,
                 stats.work_items);
      fmt::print("voxels set {} ({:.3f}% of {})\n", stats.voxels_set,
                 100.0 * double(stats.voxels_set) / double(grid.voxel_count()), grid.voxel_count());
      fmt::print("memory     {:.1f} MiB on the device\n", double(stats.device_bytes) / (1 << 20));
    }
    fmt::print("time       upload {:.2f} ms + kernels {:.2f} ms + readback {:.2f} ms = {:.2f} ms\n",
               stats.upload_ms, stats.kernels_ms, stats.readback_ms, stats.total_ms());
    std::string stages;
    for (const auto& [name, ms] : stats.stage_ms)
      stages += fmt::format("{}{} {:.2f}", stages.empty() ? "" : ", ", name, ms);
    fmt::print("stages ms  {}\n", stages);
    for (const auto& path : written) fmt::print("wrote      {}\n", path.string());
  }
  if (args.profile) fmt::print("\n{}", cl.profiler().table());
  return args.view ? run_viewer(viewer, args.output) : 0;
}

}  // namespace

Command add_voxelize(CLI::App& app) {
  auto args = std::make_shared<VoxelizeArgs>();
  CLI::App* sub = app.add_subcommand("voxelize", "Voxelize a mesh (OBJ/OFF/PLY/STL) or a scene (.json)");
  sub->add_option("input", args->input, "mesh or scene file; omitted: the built-in default scene");
  sub->add_option("-o,--output", args->output, "output volume: .nrrd, .vti, .binvox (cubic), .vox (<=256)");
  sub->add_option("--res", args->res, "voxels along the longest axis of the scene bounds (default 256)")
      ->check(CLI::Range(1u, kMaxGridDim));
  sub->add_option("--dims", args->dims, "exact grid dimensions X,Y,Z");
  sub->add_option("--bounds", args->bounds, "world box x0,y0,z0,x1,y1,z1 (default: scene bounds + margin)");
  sub->add_option(
         "--method", args->method,
         "slice (the papers' one-pass duplication), grid (Llamas: one pass per slab), slicemap (Eisemann & "
         "Decoret bit columns)")
      ->capture_default_str();
  sub->add_option("--solid", args->solid,
                  "also fill the interior (inside channel: voxels whose centre is inside): xor, late, parity "
                  "(exact on closed meshes) or flood (robust to holes)");
  sub->add_option("--slicing", args->slicing,
                  "slicemap slicing: uniform (default) or local (scene-fitted per column)");
  sub->add_option("--mode", args->mode,
                  "conservative (default: every touched voxel) or center (the papers' pixel-centre rule)");
  sub->add_option("--channels", args->channels, "comma list of occ,count,normal,material")
      ->capture_default_str();
  sub->add_option("--device", args->device, "OpenCL device P:D or name substring (also $VOXR_DEVICE)");
  sub->add_option("--report", args->report, "write a JSON report of counts and times");
  sub->add_option("--rows-per-copy", args->rows_per_copy, "rows one raster work item walks (tuning)")
      ->check(CLI::Range(1u, 4096u))
      ->capture_default_str();
  sub->add_flag("--profile", args->profile, "print a per-kernel time table");
  sub->add_flag("-q,--quiet", args->quiet, "print nothing but errors");
  sub->add_flag("--view", args->view, "open the written volume (.vti, .nrrd) in voxr-view");
  return {sub, [args] { return run_voxelize(*args); }};
}

}  // namespace voxr::cli
