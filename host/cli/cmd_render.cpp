// voxr render [SCENE] -o out.png: one image of the scene with transparent shadows and refraction by the
// chosen techniques (render/technique.h), rendered by run_render_job (eval/render_job.h, which voxr::render
// calls too), a summary of the grids and per-stage times, and with --compare-reference the error against the
// exact reference; an error image is written beside the output.
//
// --frames N renders N frames (render_job.h says how). An output name with a frame field (out_%04d.png,
// frame_pattern.h) gets every frame; without one only the last frame is written.
#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <optional>

#include "cli/commands.h"
#include "cli/frame_pattern.h"
#include "cli/option_groups.h"
#include "cli/option_groups_render.h"
#include "cli/parse_args.h"
#include "cli/progress_display.h"
#include "eval/render_job.h"
#include "io/atomic_file.h"
#include "io/image_file.h"
#include "render/distance_map_refraction.h"
#include "util/clock.h"
#include "util/error.h"
#include "util/median.h"

namespace voxr::cli {

namespace {

// `voxr render`'s flags: the job's (eval/render_job.h) and the files it writes.
struct RenderArgs : RenderJob {
  std::string output = "render.png";
  std::string size_text;  // empty: the scene camera's
  std::string report;
  bool quiet = false;
  bool progress = false;  // --progress
};

int run_render(const RenderArgs& args) {
  const auto process_start = Clock::now();
  render_job_options(args);  // the flags' errors before the files'
  const std::optional<FramePattern> pattern = parse_frame_pattern(args.output, "-o");
  // The image written last (and named in the printout and error images): the last frame's.
  const std::string last_output = pattern ? pattern->name(args.frames - 1) : args.output;
  if (!is_image_file(last_output))
    fail("{}: the image format is chosen by extension: .png or .exr", args.output);
  check_output_path(last_output);
  if (!args.report.empty()) check_output_path(args.report);
  RenderJob job = args;
  job.size =
      args.size_text.empty() ? glm::uvec2(0) : parse_size(args.size_text, "--size");  // 0: the camera's
  const ProgressDisplay progress(args.progress, args.quiet);
  RenderJobHooks hooks;
  if (progress.active()) hooks.status = [&progress](const std::string& line) { progress.show(line); };
  hooks.warning = [&progress](const std::string& w) {
    fmt::print(stderr, "{}voxr: warning: {}\n", progress.line_start(), w);
  };
  if (pattern)
    hooks.frame = [&](uint32_t f, const ImageRgba& image) { write_image(image, pattern->name(f)); };
  hooks.error_images_beside = last_output;
  RenderJobResult r = run_render_job(job, hooks);
  if (!r.profile_table.empty()) fmt::print("{}\n", r.profile_table);
  nlohmann::json& report = r.report;
  const RenderOptions& options = r.options;
  const RefractionMethod asked_refraction = r.asked_refraction;
  const bool reference_only = r.reference_only, animated = r.animated;
  const std::vector<double>& frame_ms = r.frame_ms;
  const FrameStats &stats = r.stats, &fixed_stats = r.fixed_stats;
  const std::optional<RenderTargetChoice>& target = r.target;
  const uint64_t bytes = stats.device_bytes + stats.refraction_bytes;
  const uint64_t fixed_bytes = fixed_stats.device_bytes + fixed_stats.refraction_bytes;
  const nlohmann::json compare = report.value("compare_reference", nlohmann::json::object());
  if (!pattern) write_image(r.image, args.output);
  report["ms"]["process"] = ms_since(process_start);
  if (!args.report.empty()) write_file_atomically(args.report, report.dump(2) + "\n");
  progress.clear();
  if (!args.quiet) {
    fmt::print("input      {} ({} triangles)\n", r.source, r.triangles);
    fmt::print("device     {}\n", report["device"].get<std::string>());
    fmt::print("shadows    {}{}\n", report["shadows"].get<std::string>(), r.shadow_description.suffix);
    fmt::print("refraction {}{}{}\n", report["refraction"].get<std::string>(),
               r.refraction_description.suffix,
               asked_refraction != options.refraction.method ? " (the scene has no dielectric)" : "");
    for (const std::string& line : r.shadow_description.lines) fmt::print("{}\n", line);
    for (const std::string& line : r.refraction_description.lines) fmt::print("{}\n", line);
    std::string stages;
    for (const auto& [name, ms] : r.stage_ms)
      if (median(ms) > 0.0)
        stages += fmt::format("{}{} {:.2f}", stages.empty() ? "" : ", ", name, median(ms));
    if (animated) {
      fmt::print("animation  {} frames at {:g} fps, t = 0..{:.3f} s, posing ({}) median {:.2f} ms\n",
                 args.frames, r.fps, (args.frames - 1) / r.fps,
                 reference_only ? "host"
                 : options.shadows == ShadowMethod::kReference ||
                         options.refraction.method == RefractionMethod::kImageSpace
                     ? "host, upload, BVH"
                     : "host, upload",
                 median(r.pose_ms));
    }
    fmt::print(
        "frame      {:.2f} ms{} (median of {} frame{}; min {:.2f}, max {:.2f}; {:.1f} fps)\n",
        median(frame_ms),
        reference_only ? (animated ? " incl. the BVH build" : " incl. the BVH build on the first") : "",
        frame_ms.size(), frame_ms.size() == 1 ? "" : "s", report["ms"]["frame_min"].get<double>(),
        report["ms"]["frame_max"].get<double>(), report["fps_rendered"].get<double>());
    if (!stages.empty())
      fmt::print("stages ms  {} (medians{}; host {:.2f}; {} host syncs)\n", stages,
                 reference_only ? "" : " of the device frame", stats.host_ms, stats.host_syncs);
    if (target) {
      const auto line = [](const char* what, const ResolutionChoice& c, double budget) {
        std::string trials;
        for (const ResolutionTrial& t : c.trials)
          trials += fmt::format("{}{} -> {:.4f}", trials.empty() ? "" : ", ", t.resolution, t.error);
        fmt::print("target     {} grid {}: RMSE {:.4f} {} budget {:.4f} (measured {})\n", what, c.resolution,
                   c.error, c.met ? "within" : "NOT within (the least measured)", budget, trials);
      };
      if (target->refraction) line("refraction", *target->refraction, target->refraction_budget);
      if (target->shadows) line("shadow", *target->shadows, target->shadows_budget);
      fmt::print(
          "target     RMSE {:.4f} against the reference on {}x{} pixels (target {:.4f}); search {:.0f} ms\n",
          target->sample_error, target->sample_width, target->sample_height, *args.error_target,
          target->search_ms);
      fmt::print(
          "vs 512     {:.1f} MiB and {:.2f} ms per frame on fixed 512 grids: saving {:.1f} MiB ({:.0f}%) and "
          "{:.2f} ms ({:.0f}%)\n",
          double(fixed_bytes) / (1 << 20), fixed_stats.frame_ms,
          (double(fixed_bytes) - double(bytes)) / (1 << 20),
          100.0 * (1.0 - double(bytes) / double(std::max<uint64_t>(fixed_bytes, 1))),
          fixed_stats.frame_ms - median(frame_ms),
          100.0 * (1.0 - median(frame_ms) / std::max(fixed_stats.frame_ms, 1e-9)));
    }
    const auto number_text = [](const nlohmann::json& v) {
      return v.is_number() ? fmt::format("{:.2f}", v.get<double>()) : v.get<std::string>();
    };
    if (compare.contains("refraction")) {
      const auto& c = compare["refraction"];
      const uint64_t refracted = c["refracted_pixels"].get<uint64_t>(),
                     lost = c["lost_pixels"].get<uint64_t>(),
                     method_lost = c["method_lost_pixels"].get<uint64_t>();
      const std::string events =
          c["event_mismatch_share"].is_null()
              ? fmt::format("event sequences not compared: the reference lost all {} refracted pixels",
                            refracted)
              : fmt::format(
                    "event sequence differs on {:.2f}% of {} compared pixels ({} refracted, {} lost by the "
                    "reference: not compared, {} lost by this method: differing)",
                    100.0 * c["event_mismatch_share"].get<double>(), refracted - lost, refracted, lost,
                    method_lost);
      fmt::print(
          "vs matched image RMSE {:.4f}, PSNR {} dB (exact shadows); exit direction error mean {} deg, 95th "
          "{} deg ({} pixels); {}; {} non-finite pixels\n",
          c["rmse"].get<double>(), number_text(c["psnr"]), number_text(c["angle_mean_deg"]),
          number_text(c["angle_p95_deg"]), c["angle_pixels"].get<uint64_t>(), events,
          c["nonfinite_pixels"].get<uint64_t>());
      fmt::print("wrote      {}\n", c["error_image"].get<std::string>());
    }
    if (compare.contains("shadows")) {
      const auto& c = compare["shadows"];
      fmt::print(
          "vs exact   transmittance RMSE {:.4f}, max {:.3f}, {:.2f}% of {} receivers off by > 0.05, PSNR {} "
          "dB\n",
          c["transmittance_rmse"].get<double>(), c["transmittance_max"].get<double>(),
          100.0 * c["share_over_0.05"].get<double>(), c["receivers"].get<uint64_t>(), number_text(c["psnr"]));
      fmt::print("wrote      {}\n", c["error_image"].get<std::string>());
    }
    fmt::print("process ms {:.1f}\n", report["ms"]["process"].get<double>());
    if (pattern)
      fmt::print("wrote      {} .. {}\n", pattern->name(0), last_output);
    else
      fmt::print("wrote      {}\n", args.output);
  }
  return 0;
}

// Flags only one refraction method reads are refused with another, as --mode is without --shadows voxel.
void check_method_flags(const RenderArgs& args, const CLI::App& sub) {
  if (args.refraction != "distance-maps")
    for (const char* flag : {"--layers", "--layer-res", "--dm-depth"})
      if (sub.count(flag))
        fail("{} applies to --refraction distance-maps only, not --refraction {}", flag, args.refraction);
}

}  // namespace

Command add_render(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* sub =
      app.add_subcommand("render", "Render a scene with transparent shadows and refraction (.png or .exr)");
  sub->add_option("input", args->input, "scene file (.json) or mesh; omitted: the built-in default scene");
  sub->add_option(
         "-o,--output", args->output,
         "image: .png (8-bit sRGB) or .exr (linear float); %d or %0Nd in the name: one image per frame")
      ->capture_default_str();
  add_shadows_option(*sub, args->shadows, "shadow method (the references trace exact shadows)")
      ->default_str(std::string(shadow_method_info(kDefaultShadowMethod).name));
  add_grid_option(*sub, "--shadow-res", GridKind::kShadow, args->shadow_res)->capture_default_str();
  sub->add_option("--mode", args->mode,
                  "voxel: center (default; each column's write count is its centre ray's crossings) or "
                  "conservative (over-counts)");
  add_size_option(*sub, args->size_text)->default_str("the scene camera's");
  sub->add_option("--bias", args->bias, "slabs (or depth-map texels) receivers move towards the light")
      ->check(CLI::Range(0.0f, 64.0f))
      ->capture_default_str();
  sub->add_option("--normal-offset", args->normal_offset, "columns receivers move off their surface")
      ->check(CLI::Range(0.0f, 64.0f))
      ->capture_default_str();
  std::string refractions;
  for (const RefractionMethodInfo& info : kRefractionMethods)
    refractions += fmt::format("{}{} ({})", refractions.empty() ? "" : "; ", info.name, info.summary);
  sub->add_option("--refraction", args->refraction, refractions)->capture_default_str();
  add_grid_option(*sub, "--res", GridKind::kRefraction, args->res)->capture_default_str();
  std::string refraction_grids;
  for (const RefractionGridInfo& info : kRefractionGrids)
    refraction_grids +=
        fmt::format("{}{} ({})", refraction_grids.empty() ? "" : "; ", info.name, info.summary);
  sub->add_option("--refraction-grid", args->refraction_grid, "voxel refraction's grids: " + refraction_grids)
      ->capture_default_str();
  sub->add_option(
         "--coarse-res", args->coarse_res,
         "--refraction-grid fitted: voxels along the coarse grid's longest side (the whole scene); 0: "
         "--res/2")
      ->check(CLI::Range(0u, kRefractionResMax))
      ->capture_default_str();
  sub->add_option(
         "--step", args->step,
         "voxel refraction's march: papers (fixed step h / cos theta along the dominant axis) or dda "
         "(exact voxel traversal)")
      ->capture_default_str();
  sub->add_option("--normals", args->normals,
                  "voxel refraction's boundary normals: voxel (the voxel's normal sum, the papers) or smooth "
                  "(3x3x3 neighbours weighted by distance)")
      ->capture_default_str();
  sub->add_option(
         "--angle-threshold", args->angle_threshold,
         "voxel-multi: degrees a boundary voxel's normal must turn from the last refraction normal to "
         "count as a new interface within one boundary run")
      ->check(CLI::Range(0.0f, 180.0f))
      ->capture_default_str();
  sub->add_option("--layers", args->layers,
                  "distance-maps: depth-peeled layers of the refractor's cube distance map (surfaces hidden "
                  "from the reference point behind more are missed)")
      ->check(CLI::Range(1u, kDistanceMapMaxLayers))
      ->capture_default_str();
  sub->add_option("--layer-res", args->layer_res, "distance-maps: texels per cube-map face side")
      ->check(CLI::Range(kDistanceMapMinRes, kDistanceMapMaxRes))
      ->capture_default_str();
  sub->add_option("--dm-depth", args->dm_depth,
                  "distance-maps: interfaces a path meets at most (then it is lost)")
      ->check(CLI::Range(1u, uint32_t(VOXR_PATH_MAX_EVENTS)))
      ->capture_default_str();
  sub->add_option(
         "--frames", args->frames,
         "frames to render: an animated scene at t = f / fps (re-voxelized every frame), a static one "
         "the same frame again (warm timing); median, min, max and per-stage times. With a frame "
         "field in -o (out_%04d.png) every frame is written, else the last")
      ->check(CLI::Range(1u, 100000u))
      ->capture_default_str();
  sub->add_option(
         "--error-target", args->error_target,
         "choose the smallest refraction and shadow grids (16..512) whose frame is within image RMSE "
         "E of the Embree reference, measured on a quarter of the pixels; reports the saving against "
         "512 grids (render_error_target.h)")
      ->check(CLI::Range(0.0, 1.0));
  sub->add_flag(
      "--compare-reference", args->compare_reference,
      "measure against the Embree reference: refraction against the matched reference (image, exit "
      "directions, event sequences), or without refraction the shadows at the same receivers; writes "
      "OUT.error.png");
  add_device_option(*sub, args->device);
  add_report_options(*sub, args->report, args->profile, args->quiet, "times, grids, light grid and errors");
  sub->add_flag(
      "--progress", args->progress,
      "show each step (reading, rendering, frame i/n) on stderr even with -q or when stderr is not a "
      "terminal: one line per step with the seconds since the start");
  return {sub, [args, sub] {
            check_method_flags(*args, *sub);
            args->grids_given = sub->count("--res") + sub->count("--shadow-res") > 0;
            return run_render(*args);
          }};
}

}  // namespace voxr::cli
