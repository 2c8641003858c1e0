#include "cli/bench_shadows.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "bench/report_fields.h"
#include "cl/cl_runtime.h"
#include "cli/bench_support.h"
#include "cli/commands.h"
#include "cli/option_groups.h"
#include "cli/parse_args.h"
#include "cli/process.h"
#include "io/atomic_file.h"

namespace voxr::cli {

namespace fs = std::filesystem;

namespace {

// Debian's python3, where python3-matplotlib is installed (a pyenv or venv python3 first on PATH may lack
// it).
constexpr const char* kSystemPython = "/usr/bin/python3";

using Row = ShadowBenchRow;

}  // namespace

int run_bench_shadows(const BenchShadowsArgs& args) {
  ShadowBenchOptions options = args.bench;
  options.size = parse_size(args.size, "--size");
  ClRuntime cl(args.device);
  const std::string device = fmt::format("{} ({}, driver {})", cl.device().name, cl.device().platform_name,
                                         cl.device().driver_version);
  fmt::print("device: {}\n", device);
  FreshRenders fresh;
  if (args.fresh > 0)
    fresh = [&args](std::vector<std::string> render_args) {
      render_args.insert(render_args.end(), {"--size", args.size});
      return time_fresh_renders(render_args, args.fresh, args.device, "bench-shadows");
    };
  const ShadowBenchRun run = measure_shadows(cl, options, fresh);
  const std::vector<Row>& rows = run.rows;
  std::string fresh_table;
  for (const FreshRenderTimes& f : run.fresh) fresh_table += fresh_table_row(f.scene, f.triangles, f.wall_ms);

  std::ostringstream csv;
  csv << "scene,method,mode,resolution,frame_ms,frame_ms_min,frame_ms_max,rmse,max_abs,share_over_0.05,psnr,"
         "receivers,triangles,device_bytes,light_grid\n";
  for (const Row& r : rows)
    csv << fmt::format("{},{},{},{},{:.3f},{:.3f},{:.3f},{:.5f},{:.4f},{:.5f},{},{},{},{},\"{}\"\n", r.scene,
                       r.method, r.mode, r.resolution, r.frame_ms, r.frame_min, r.frame_max, r.error.rmse,
                       r.error.max_abs, r.error.share_over_threshold, number_cell(r.psnr, 2),
                       r.error.receivers, r.triangles, r.device_bytes, r.light_grid);
  std::ostringstream md;
  md << fmt::format(
      "# voxr bench shadows\n\nDevice: {}. Image {}. Warm frames: median of {} after {} warm-up "
      "[min, max], wall time of one whole frame read back to the host. Errors at the visible "
      "receivers against Embree's exact transmittance at the same points.\n\n",
      device, args.size, args.bench.repeat, args.bench.warmup);
  md << "| scene | method | mode | res | frame ms | [min, max] | T RMSE | T max | > 0.05 | PSNR dB | light "
        "grid |\n"
        "|---|---|---|---:|---:|---|---:|---:|---:|---:|---|\n";
  for (const Row& r : rows)
    md << fmt::format(
        "| {} | {} | {} | {} | {:.2f} | [{:.2f}, {:.2f}] | {:.4f} | {:.3f} | {:.2f}% | {} | {} |\n", r.scene,
        r.method, r.mode, r.resolution ? std::to_string(r.resolution) : "-", r.frame_ms, r.frame_min,
        r.frame_max, r.error.rmse, r.error.max_abs, 100.0 * r.error.share_over_threshold,
        number_cell(r.psnr, 2), r.light_grid);
  if (!fresh_table.empty())
    md << "\nFresh processes, `voxr render SCENE --shadows voxel --shadow-res 256 --size " << args.size
       << "` (wall ms, median [min, max] of " << args.fresh << "; includes opening the device, loading the "
       << "programs from the cache, reading the scene and writing the PNG):\n\n| scene | triangles | ms | "
          "min | "
          "max |\n|---|---:|---:|---:|---:|\n"
       << fresh_table;
  write_file_atomically(args.out + ".csv", csv.str());
  write_file_atomically(args.out + ".md", md.str());
  fmt::print("wrote {}.csv\nwrote {}.md\n", args.out, args.out);
  const fs::path script = fs::path(VOXR_SOURCE_DIR) / "bench" / "shadow_charts.py";
  if (fs::exists(script)) {
    const int status = run_program({kSystemPython, script.string(), args.out + ".csv", args.out + "-charts"});
    if (status != 0)
      fmt::print(stderr, "voxr: warning: the charts were not drawn ({} failed)\n", script.string());
  }
  return 0;
}

Command add_bench_shadows(CLI::App& bench) {
  auto shadows = std::make_shared<BenchShadowsArgs>();
  CLI::App* sh = bench.add_subcommand(
      "shadows", "Shadow methods x shadow resolutions x scenes: frame time against error vs Embree");
  sh->add_option("--scenes", shadows->bench.scenes, "scene files (default: the built-in scene)")
      ->delimiter(',')
      ->capture_default_str();
  add_grid_option(*sh, "--res", GridKind::kShadow, shadows->bench.resolutions);
  sh->add_option("--methods", shadows->bench.methods,
                 "voxel-center, voxel-conservative, uniform, filter, opaque, voxel-exact")
      ->delimiter(',')
      ->capture_default_str();
  add_size_option(*sh, shadows->size)->capture_default_str();
  add_device_option(*sh, shadows->device);
  add_out_prefix_option(*sh, shadows->out, "PREFIX.csv, PREFIX.md, PREFIX-charts/");
  add_repeat_options(*sh, shadows->bench.repeat, shadows->bench.warmup);
  add_fresh_option(*sh, shadows->fresh, "voxr render SCENE --shadows voxel --shadow-res 256");
  return {sh, [shadows] { return run_bench_shadows(*shadows); }};
}

}  // namespace voxr::cli
