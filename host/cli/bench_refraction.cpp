#include "cli/bench_refraction.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "bench/report_fields.h"
#include "cl/cl_runtime.h"
#include "cli/bench_support.h"
#include "cli/commands.h"
#include "cli/option_groups.h"
#include "cli/option_groups_render.h"
#include "cli/parse_args.h"
#include "cli/process.h"
#include "io/atomic_file.h"
#include "render/refraction_method.h"
#include "render/shadow_method.h"

namespace voxr::cli {

namespace fs = std::filesystem;

namespace {

// Debian's python3, where python3-matplotlib is installed (a pyenv or venv python3 first on PATH may lack
// it).
constexpr const char* kSystemPython = "/usr/bin/python3";

// What the frame includes, said once in the Markdown.
constexpr const char* kFrameIncludes =
    "one whole frame: voxelize the scene with normals and materials (voxel methods; no inside channel: media "
    "are told by the voxel normals' winding) + rasterize the camera's "
    "visibility + refract + the shadow method's light structure and lookup + shade + read the image back";

using Row = RefractionBenchRow;

// The benchmark's options with the size parsed. Throws voxr::Error naming what is wrong when a method, the
// shadow method, the size or a scene file is not valid; touches no device.
RefractionBenchOptions check_bench_refraction_args(const BenchRefractionArgs& args) {
  RefractionBenchOptions options = args.bench;
  options.size = parse_size(args.size, "--size");
  check_refraction_bench(options);
  return options;
}

}  // namespace

int run_bench_refraction(const BenchRefractionArgs& args) {
  // Everything the command line says is checked before the device is opened.
  const RefractionBenchOptions options = check_bench_refraction_args(args);
  const std::string load_before = load_average_text();
  ClRuntime cl(args.device);
  const std::string device = fmt::format("{} ({})", cl.device().name, cl.device().platform_name);
  const std::string driver = cl.device().driver_version;
  const std::string started = utc_now();
  fmt::print("device: {}, driver {}\n", device, driver);
  FreshRenders fresh;
  if (args.fresh > 0)
    fresh = [&args](std::vector<std::string> render_args) {
      render_args.insert(render_args.end(), {"--size", args.size});
      return time_fresh_renders(render_args, args.fresh, args.device, "bench-refraction");
    };
  const RefractionBenchRun run = measure_refraction(cl, options, fresh);
  const std::vector<Row>& rows = run.rows;
  std::string fresh_table, precompute_table;
  for (const FreshRenderTimes& f : run.fresh) fresh_table += fresh_table_row(f.scene, f.triangles, f.wall_ms);
  for (const PrecomputeTime& p : run.precompute)
    precompute_table += fmt::format("| {} | {} | {:.1f} |\n", p.scene, p.triangles, p.ms);
  const std::string load_after = load_average_text();

  std::ostringstream csv;
  csv << "scene,triangles,method,step,normals,res,frame_ms,frame_ms_min,frame_ms_max,refraction_ms,dm_layers_"
         "ms,"
         "rmse,psnr,"
         "angle_mean_deg,angle_p95_deg,angle_pixels,event_mismatch,refracted_pixels,nonfinite,grid_bytes\n";
  for (const Row& r : rows)
    csv << fmt::format("{},{},{},{},{},{},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{},{},{},{},{},{},{},{},{}\n",
                       r.scene, r.triangles, r.method, r.step, r.normals, resolution_cell(r.resolution),
                       r.frame_ms, r.frame_min, r.frame_max, r.refraction_ms, r.layers_ms,
                       number_cell(r.error.rmse, 6), number_cell(r.error.psnr, 3),
                       number_cell(r.error.angle_mean_deg, 4), number_cell(r.error.angle_p95_deg, 4),
                       r.error.angle_pixels, number_cell(r.error.event_mismatch_share, 5),
                       r.error.refracted_pixels, r.error.nonfinite_pixels, r.grid_bytes);

  std::ostringstream md;
  md << fmt::format(
      "# voxr bench refraction\n\n"
      "- Device: {}, driver {}\n- Date: {}\n- Command: `{}`\n- Machine load (/proc/loadavg 1, 5, 15 min): "
      "{} before, {} after\n- Image {}, shadows {} at shadow resolution {}. Warm frames: median of {} after "
      "{} warm-up [min, max].\n\n",
      device, driver, started, command_line(), load_before, load_after, args.size,
      shadow_method_info(parse_shadow_method(options.shadows)).name, options.shadow_res, options.repeat,
      options.warmup);
  md << "The frame is " << kFrameIncludes
     << ". The refraction column is the trace kernel alone (the \"refraction\" stage); dm-layers is "
        "distance-maps' rendering of its cube maps every frame (the \"dm-layers\" stage: binning, peeling, "
        "resolving). "
        "Errors are measured on one more frame of each method rendered with the exact (Embree) shadow "
        "transmittance at its path ends, against the matched reference (the voxel methods' own model, "
        "traced exactly with Embree), so they are refraction's alone, not the shadow method's. "
        "reference-matched's frame is its BVH build + tracing + shadow rays + shading on the host's cores. "
        "Angles: exit directions where both paths leave to the environment; events: share of refracted "
        "pixels whose interface count or total internal reflection differs.\n";
  std::string scene;
  for (const Row& r : rows) {
    if (r.scene != scene) {
      scene = r.scene;
      md << fmt::format(
          "\n## {} ({} triangles)\n\n| method | step | normals | res | frame ms | [min, max] | refraction ms "
          "| dm-layers ms | "
          "RMSE | PSNR dB | angle mean deg | angle p95 deg | event mismatch | non-finite | grid MiB |\n"
          "|---|---|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
          r.scene, r.triangles);
    }
    md << fmt::format(
        "| {} | {} | {} | {} | {:.2f} | [{:.2f}, {:.2f}] | {:.2f} | {} | {} | {} | {} | {} | {}% | {} | "
        "{:.2f} |\n",
        r.method, r.step.empty() ? "-" : r.step, r.normals.empty() ? "-" : r.normals,
        r.resolution ? std::to_string(r.resolution) : "-", r.frame_ms, r.frame_min, r.frame_max,
        r.refraction_ms, r.layers_ms > 0.0 ? number_cell(r.layers_ms, 2) : "-", number_cell(r.error.rmse, 4),
        number_cell(r.error.psnr, 2), number_cell(r.error.angle_mean_deg, 2),
        number_cell(r.error.angle_p95_deg, 2), number_cell(100.0 * r.error.event_mismatch_share, 2),
        r.error.nonfinite_pixels, double(r.grid_bytes) / (1 << 20));
  }
  if (!precompute_table.empty())
    md << "\nImage-space's per-scene precompute, Wyman's d_N by ray casting (host, not in the frame):\n\n"
          "| scene | triangles | ms |\n|---|---:|---:|\n"
       << precompute_table;
  if (!fresh_table.empty())
    md << "\nFresh processes, `voxr render SCENE --refraction "
       << refraction_method_info(kDefaultRefractionMethod).name << " --res 256 --shadows " << options.shadows
       << " --shadow-res " << options.shadow_res << " --size " << args.size
       << "` (wall ms, median [min, max] of " << args.fresh
       << "; includes opening the device, loading the programs from the cache, reading the scene and writing "
          "the PNG):\n\n| scene | triangles | ms | min | max |\n|---|---:|---:|---:|---:|\n"
       << fresh_table;
  write_file_atomically(args.out + ".csv", csv.str());
  write_file_atomically(args.out + ".md", md.str());
  fmt::print("wrote {}.csv\nwrote {}.md\n", args.out, args.out);
  std::fflush(stdout);
  const fs::path script = fs::path(VOXR_SOURCE_DIR) / "bench" / "shadow_charts.py";
  if (fs::exists(script)) {
    for (const char* error : {"rmse", "angle_mean_deg"}) {
      const int status =
          run_program({kSystemPython, script.string(), args.out + ".csv", args.out + "-charts/" + error,
                       "--error-column", error, "--time-column", "frame_ms", "--group-columns",
                       "method,step,normals", "--label-column", "res", "--reference", "reference-matched"});
      if (status != 0)
        fmt::print(stderr, "voxr: warning: the {} charts were not drawn ({} failed)\n", error,
                   script.string());
    }
  }
  return 0;
}

Command add_bench_refraction(CLI::App& bench) {
  auto a = std::make_shared<BenchRefractionArgs>();
  CLI::App* sub = bench.add_subcommand(
      "refraction",
      "Refraction methods x grid resolutions x scenes: frame time against error vs the matched reference");
  sub->add_option("--scenes", a->bench.scenes, "scene files")->delimiter(',')->capture_default_str();
  sub->add_option("--methods", a->bench.methods, kRefractionBenchMethodHelp)
      ->delimiter(',')
      ->capture_default_str();
  add_grid_option(*sub, "--res", GridKind::kRefraction, a->bench.resolutions);
  add_shadows_option(*sub, a->bench.shadows,
                     "the timed frames' shadow method (errors always use the exact ones)")
      ->capture_default_str();
  add_grid_option(*sub, "--shadow-res", GridKind::kShadow, a->bench.shadow_res)->capture_default_str();
  add_size_option(*sub, a->size)->capture_default_str();
  add_device_option(*sub, a->device);
  add_out_prefix_option(*sub, a->out, "PREFIX.csv, PREFIX.md, PREFIX-charts/");
  add_repeat_options(*sub, a->bench.repeat, a->bench.warmup);
  add_fresh_option(*sub, a->fresh,
                   fmt::format("voxr render SCENE --refraction {} --res 256",
                               refraction_method_info(kDefaultRefractionMethod).name));
  return {sub, [a] { return run_bench_refraction(*a); }};
}

}  // namespace voxr::cli
