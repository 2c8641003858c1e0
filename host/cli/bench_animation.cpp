#include "cli/bench_animation.h"

#include <fmt/format.h>

#include <array>
#include <sstream>

#include "bench/report_fields.h"
#include "cl/cl_runtime.h"
#include "cli/bench_support.h"
#include "cli/commands.h"
#include "cli/option_groups.h"
#include "cli/parse_args.h"
#include "io/atomic_file.h"

namespace voxr::cli {

int run_bench_animation(const BenchAnimationArgs& args) {
  AnimationBenchOptions options = args.bench;
  options.size = parse_size(args.size, "--size");
  const std::string started = utc_now();
  const std::array<double, 3> load_start = load_averages();
  ClRuntime cl(args.device);
  const std::string device = fmt::format("{} ({}, driver {})", cl.device().name, cl.device().platform_name,
                                         cl.device().driver_version);
  fmt::print("device: {}\n", device);
  FreshRenders fresh;
  if (args.fresh > 0)
    fresh = [&args](std::vector<std::string> render_args) {
      render_args.insert(render_args.end(), {"--size", args.size});
      return time_fresh_renders(render_args, args.fresh, args.device, "bench-animation");
    };
  const std::vector<AnimationBenchRow> rows = measure_animation(cl, options, fresh);
  const std::array<double, 3> load_end = load_averages();

  std::ostringstream csv;
  csv << "scene,triangles,refraction,frames,scene_fps,frame_ms,frame_ms_min,frame_ms_max,fps,pose_ms,"
         "fresh_process_ms,stages_ms\n";
  for (const AnimationBenchRow& r : rows)
    csv << fmt::format("{},{},{},{},{:g},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.0f},\"{}\"\n", r.scene,
                       r.triangles, r.refraction, args.bench.frames, r.fps_scene, r.frame_ms, r.frame_min,
                       r.frame_max, 1000.0 / r.frame_ms, r.pose_ms, r.fresh_ms, stage_text(r.stages, "; "));
  std::ostringstream md;
  md << fmt::format(
      "# voxr bench animation\n\n{}. Command: `voxr bench animation --frames {} --size {} --fresh {} --out "
      "{}{}`. "
      "Device: {}. Load average (1, 5, 15 min) {:.2f} {:.2f} {:.2f} at the start, {:.2f} {:.2f} {:.2f} at "
      "the "
      "end.\n\n"
      "Every frame is posed at t = f / fps on the host and re-voxelized on the device (nothing precomputed): "
      "voxel shadows (centre mode, 256 columns), voxel-multi refraction (res 256) where the scene has glass. "
      "Frame: wall time of one frame, image read back; pose: host posing + upload (set_scene); stages: "
      "profiled device ms, medians over the frames. The first frame grows the device buffers: it is usually "
      "the max.\n\n",
      started, args.bench.frames, args.size, args.fresh, args.out,
      args.device.empty() ? "" : " --device " + args.device, device, load_start[0], load_start[1],
      load_start[2], load_end[0], load_end[1], load_end[2]);
  md << "| scene | triangles | refraction | frame ms | [min, max] | fps | pose ms | fresh process ms | "
        "stages "
        "ms (medians) |\n|---|---:|---|---:|---|---:|---:|---:|---|\n";
  for (const AnimationBenchRow& r : rows)
    md << fmt::format("| {} | {} | {} | {:.1f} | [{:.1f}, {:.1f}] | {:.2f} | {:.1f} | {} | {} |\n", r.scene,
                      r.triangles, r.refraction, r.frame_ms, r.frame_min, r.frame_max, 1000.0 / r.frame_ms,
                      r.pose_ms, r.fresh_ms < 0 ? "-" : fmt::format("{:.0f}", r.fresh_ms),
                      stage_text(r.stages, ", "));
  md << fmt::format(
      "\nFresh process: `voxr render SCENE --frames {} --size {}` (opening the device, programs from the "
      "cache, reading the scene, {} frames, the last image written), median of {}.\n",
      args.bench.frames, args.size, args.bench.frames, args.fresh);
  write_file_atomically(args.out + ".csv", csv.str());
  write_file_atomically(args.out + ".md", md.str());
  fmt::print("wrote {}.csv\nwrote {}.md\n", args.out, args.out);
  return 0;
}

Command add_bench_animation(CLI::App& bench) {
  auto args = std::make_shared<BenchAnimationArgs>();
  CLI::App* sub = bench.add_subcommand(
      "animation", "Deforming scenes re-voxelized every frame: frame rate, per-stage times, fresh process");
  sub->add_option("--scenes", args->bench.scenes, "animated scene files")
      ->delimiter(',')
      ->capture_default_str();
  sub->add_option("--frames", args->bench.frames, "frames per scene")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  add_size_option(*sub, args->size)->capture_default_str();
  add_device_option(*sub, args->device);
  add_out_prefix_option(*sub, args->out, "PREFIX.csv and PREFIX.md");
  add_fresh_option(*sub, args->fresh, "voxr render SCENE --frames N --size SIZE");
  return {sub, [args] { return run_bench_animation(*args); }};
}

}  // namespace voxr::cli
