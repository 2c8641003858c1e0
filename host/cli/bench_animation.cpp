#include "cli/bench_animation.h"

#include <fmt/chrono.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <sstream>

#include "cl/cl_runtime.h"
#include "cli/bench_support.h"
#include "cli/commands.h"
#include "cli/option_groups.h"
#include "cli/parse_args.h"
#include "core/animation.h"
#include "core/scene.h"
#include "io/atomic_file.h"
#include "render/environment_map.h"
#include "render/frame_renderer.h"
#include "render/render_scene.h"
#include "util/clock.h"
#include "util/median.h"

namespace voxr::cli {

namespace {

struct Row {
  std::string scene, refraction;
  uint64_t triangles = 0;
  double fps_scene = 0;  // the scene's frames per second (animation time)
  double frame_ms = 0, frame_min = 0, frame_max = 0, pose_ms = 0;
  std::map<std::string, double> stages;  // medians
  double fresh_ms = -1;                  // median wall ms of the fresh processes; -1: none
};

std::string stage_text(const std::map<std::string, double>& stages, const char* separator) {
  std::string out;
  for (const auto& [name, ms] : stages)
    if (ms > 0.0) out += fmt::format("{}{} {:.2f}", out.empty() ? "" : separator, name, ms);
  return out;
}

}  // namespace

int run_bench_animation(const BenchAnimationArgs& args) {
  const std::string started = utc_now();
  const std::array<double, 3> load_start = load_averages();
  ClRuntime cl(args.device);
  const std::string device = fmt::format("{} ({}, driver {})", cl.device().name, cl.device().platform_name,
                                         cl.device().driver_version);
  fmt::print("device: {}\n", device);
  const glm::uvec2 size = parse_size(args.size, "--size");

  std::vector<Row> rows;
  for (const std::string& scene_name : args.scenes) {
    const Scene scene = load_input(scene_name);
    if (!is_animated(scene)) fail("{}: the scene is not animated (no mesh has an \"animation\")", scene_name);
    const std::vector<Material>& materials = scene.materials;
    const TriangleSoup rest = scene_triangles(scene);
    validate_soup(rest, scene.source);
    const CameraFrame camera = make_camera_frame(scene.camera, rest.anchor, rest.bounds(), size.x, size.y);
    const RenderLight light =
        render_light(scene.light, make_environment_map(scene.environment).mean(), rest.anchor);
    RenderOptions options;  // voxel shadows, centre mode, 256 columns
    options.refraction.method =
        has_dielectric(rest, materials) ? RefractionMethod::kVoxelMulti : RefractionMethod::kNone;
    FrameRenderer renderer(cl);
    renderer.prepare(options);
    renderer.set_environment(make_environment_map(scene.environment));

    Row row;
    row.scene = scene_label(scene_name);
    row.refraction = refraction_method_info(options.refraction.method).name;
    row.triangles = rest.triangle_count();
    row.fps_scene = scene.fps;
    std::vector<double> frame_ms, pose_ms;
    std::map<std::string, std::vector<double>> stage_ms;
    TriangleSoup posed;
    for (int f = 0; f < args.frames; ++f) {
      const auto pose_start = Clock::now();
      pose_scene(scene, f / scene.fps, rest.anchor, posed);
      renderer.set_scene(posed, materials);
      pose_ms.push_back(ms_since(pose_start));
      FrameStats stats;
      renderer.render(light, camera, options, &stats);
      frame_ms.push_back(stats.frame_ms);
      for (const auto& [name, ms] : stats.stage_ms) stage_ms[name].push_back(ms);
    }
    row.frame_ms = median(frame_ms);
    row.frame_min = *std::min_element(frame_ms.begin(), frame_ms.end());
    row.frame_max = *std::max_element(frame_ms.begin(), frame_ms.end());
    row.pose_ms = median(pose_ms);
    for (const auto& [name, ms] : stage_ms) row.stages[name] = median(ms);
    fmt::print(
        "{}: {} triangles, {} frames, {}: frame {:.1f} ms [{:.1f}, {:.1f}], {:.2f} fps, pose {:.1f} ms; "
        "stages {} (load {:.2f})\n",
        row.scene, row.triangles, args.frames, row.refraction, row.frame_ms, row.frame_min, row.frame_max,
        1000.0 / row.frame_ms, row.pose_ms, stage_text(row.stages, ", "), load_averages()[0]);
    std::fflush(stdout);
    if (args.fresh > 0) {
      const std::vector<double> wall =
          time_fresh_renders({scene_name, "--frames", std::to_string(args.frames), "--size", args.size},
                             args.fresh, args.device, "bench-animation");
      row.fresh_ms = median(wall);
      fmt::print("  fresh `voxr render --frames {}`: {:.0f} ms\n", args.frames, row.fresh_ms);
    }
    rows.push_back(row);
  }
  const std::array<double, 3> load_end = load_averages();

  std::ostringstream csv;
  csv << "scene,triangles,refraction,frames,scene_fps,frame_ms,frame_ms_min,frame_ms_max,fps,pose_ms,"
         "fresh_process_ms,stages_ms\n";
  for (const Row& r : rows)
    csv << fmt::format("{},{},{},{},{:g},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.0f},\"{}\"\n", r.scene,
                       r.triangles, r.refraction, args.frames, r.fps_scene, r.frame_ms, r.frame_min,
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
      started, args.frames, args.size, args.fresh, args.out,
      args.device.empty() ? "" : " --device " + args.device, device, load_start[0], load_start[1],
      load_start[2], load_end[0], load_end[1], load_end[2]);
  md << "| scene | triangles | refraction | frame ms | [min, max] | fps | pose ms | fresh process ms | "
        "stages "
        "ms (medians) |\n|---|---:|---|---:|---|---:|---:|---:|---|\n";
  for (const Row& r : rows)
    md << fmt::format("| {} | {} | {} | {:.1f} | [{:.1f}, {:.1f}] | {:.2f} | {:.1f} | {} | {} |\n", r.scene,
                      r.triangles, r.refraction, r.frame_ms, r.frame_min, r.frame_max, 1000.0 / r.frame_ms,
                      r.pose_ms, r.fresh_ms < 0 ? "-" : fmt::format("{:.0f}", r.fresh_ms),
                      stage_text(r.stages, ", "));
  md << fmt::format(
      "\nFresh process: `voxr render SCENE --frames {} --size {}` (opening the device, programs from the "
      "cache, reading the scene, {} frames, the last image written), median of {}.\n",
      args.frames, args.size, args.frames, args.fresh);
  write_file_atomically(args.out + ".csv", csv.str());
  write_file_atomically(args.out + ".md", md.str());
  fmt::print("wrote {}.csv\nwrote {}.md\n", args.out, args.out);
  return 0;
}

Command add_bench_animation(CLI::App& bench) {
  auto args = std::make_shared<BenchAnimationArgs>();
  CLI::App* sub = bench.add_subcommand(
      "animation", "Deforming scenes re-voxelized every frame: frame rate, per-stage times, fresh process");
  sub->add_option("--scenes", args->scenes, "animated scene files")->delimiter(',')->capture_default_str();
  sub->add_option("--frames", args->frames, "frames per scene")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  add_size_option(*sub, args->size)->capture_default_str();
  add_device_option(*sub, args->device);
  add_out_prefix_option(*sub, args->out, "PREFIX.csv and PREFIX.md");
  add_fresh_option(*sub, args->fresh, "voxr render SCENE --frames N --size SIZE");
  return {sub, [args] { return run_bench_animation(*args); }};
}

}  // namespace voxr::cli
