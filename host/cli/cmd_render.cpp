// voxr render [SCENE] -o out.png: one image of the scene with transparent shadows and refraction by the
// chosen techniques (render/technique.h), in one frame loop through FrameRenderer for every method, the
// Embree references (--shadows reference, --refraction reference|reference-full) included, a summary of the
// grids and per-stage times, and with --compare-reference the error against the exact reference: for
// refraction, image RMSE/PSNR against the matched reference, exit direction error, event-sequence mismatches
// and non-finite pixels; without refraction, the shadows' transmittance at the same receiver points (RMSE,
// maximum, share off by more than 0.05, image PSNR). An error image is written beside the output.
//
// Like voxr voxelize, the device is opened and the programs built on a second thread while the scene is read.
//
// --frames N renders N frames. An animated scene (core/animation.h) is posed at t = f / fps for frame f and
// handed to the renderer again (re-voxelized on the device: nothing is precomputed; the references rebuild
// their BVH every frame, image-space refraction ray casts d_N every frame); the camera and light stay those
// of frame 0. A static scene renders the same frame N times (warm timing). An output name with a frame
// field (out_%04d.png, frame_pattern.h) gets every frame; without one only the last frame is written.
#include <fmt/format.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>
#include <optional>

#include "cl/cl_runtime.h"
#include "cli/commands.h"
#include "cli/frame_pattern.h"
#include "cli/option_groups.h"
#include "cli/option_groups_render.h"
#include "cli/parse_args.h"
#include "cli/prepared_runtime.h"
#include "core/animation.h"
#include "core/default_scene.h"
#include "core/scene.h"
#include "eval/reference_comparison.h"
#include "eval/render_case.h"
#include "eval/render_error_target.h"
#include "io/atomic_file.h"
#include "io/image_file.h"
#include "metrics/image_metrics.h"
#include "metrics/refraction_metrics.h"
#include "reference/reference_refraction.h"
#include "render/distance_map_refraction.h"
#include "render/environment_map.h"
#include "render/frame_renderer.h"
#include "render/light_frame.h"
#include "render/placement_error.h"
#include "render/render_scene.h"
#include "util/clock.h"
#include "util/file_extension.h"
#include "util/median.h"

namespace voxr::cli {

namespace {

struct RenderArgs {
  std::string input;  // empty: the built-in default scene
  std::string output = "render.png";
  std::string shadows;  // empty: kDefaultShadowMethod (the references trace exact shadows and take no other)
  uint32_t shadow_res = 256;
  std::string mode;  // empty: center
  std::string size;  // empty: the scene camera's
  std::string device;
  std::string report;
  float bias = kDefaultShadowBias;
  float normal_offset = kDefaultNormalOffset;
  std::string refraction{refraction_method_info(kDefaultRefractionMethod).name};
  uint32_t res = 256;
  std::string refraction_grid = "fitted";
  uint32_t coarse_res = 0;
  std::string step = "papers";
  std::string normals = "smooth";
  float angle_threshold = 60.0f;
  uint32_t layers = 4;
  uint32_t layer_res = 128;
  uint32_t dm_depth = VOXR_PATH_MAX_EVENTS;
  uint32_t frames = 1;
  std::optional<double> error_target;  // image RMSE against the reference (render_error_target.h)
  bool grids_given = false;            // --res or --shadow-res on the command line
  bool compare_reference = false;
  bool profile = false;
  bool quiet = false;
};

// "out/a.png" -> "out/a.error.png"
std::filesystem::path beside(const std::string& output, const std::string& tag) {
  std::filesystem::path p(output);
  return p.parent_path() / (p.stem().string() + "." + tag + p.extension().string());
}

// A number, or "inf" / "nan" as text (JSON has neither).
nlohmann::json finite_or_inf(double v) {
  if (std::isnan(v)) return "nan";
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json("inf");
}

RenderOptions render_options(const RenderArgs& args) {
  RenderOptions options;
  options.shadows = args.shadows.empty() ? kDefaultShadowMethod : parse_shadow_method(args.shadows);
  if (!args.mode.empty() && options.shadows != ShadowMethod::kVoxel)
    fail("--mode applies to --shadows voxel only (the light voxelizer's rule)");
  options.mode = parse_raster_mode(args.mode.empty() ? "center" : args.mode);
  options.shadow_resolution = args.shadow_res;
  options.bias = args.bias;
  options.normal_offset = args.normal_offset;
  options.refraction.method = parse_refraction_method(args.refraction);
  options.refraction.resolution = args.res;
  options.refraction.grid = parse_refraction_grid(args.refraction_grid);
  options.refraction.coarse_resolution = args.coarse_res;
  options.refraction.step = parse_step_rule(args.step);
  options.refraction.normals = parse_normal_kind(args.normals);
  options.refraction.angle_threshold_deg = args.angle_threshold;
  options.refraction.layers = args.layers;
  options.refraction.layer_res = args.layer_res;
  options.refraction.max_events = args.dm_depth;
  options.keep_samples = args.compare_reference;
  return options;
}

int run_render(const RenderArgs& args) {
  const auto process_start = Clock::now();
  RenderOptions options = render_options(args);
  const std::optional<FramePattern> pattern = parse_frame_pattern(args.output, "-o");
  // The image written last (and named in the printout and error images): the last frame's.
  const std::string last_output = pattern ? pattern->name(args.frames - 1) : args.output;
  if (!is_image_file(last_output))
    fail("{}: the image format is chosen by extension: .png or .exr", args.output);
  check_output_path(last_output);
  if (!args.report.empty()) check_output_path(args.report);
  const glm::uvec2 size =
      args.size.empty() ? glm::uvec2(0) : parse_size(args.size, "--size");  // 0: the camera's
  if (!args.input.empty()) {
    std::error_code ec;
    if (!std::filesystem::exists(args.input, ec)) fail("{}: no such file", args.input);
  }
  const RefractionMethod asked_refraction = options.refraction.method;
  const bool host_refraction = is_reference_refraction(asked_refraction);
  // The reference refractions finish the frame on the host (their technique's render_on_host); --shadows
  // reference alone runs the device frame with the exact transmittance traced for its samples.
  const bool reference_only = host_refraction;
  if (host_refraction && !args.shadows.empty() && options.shadows != ShadowMethod::kReference)
    fail("--refraction {} traces exact shadows; --shadows {} does not apply (leave it out or say reference)",
         args.refraction, args.shadows);
  if (host_refraction) options.shadows = ShadowMethod::kReference;
  const bool exact_shadows =
      options.shadows == ShadowMethod::kReference || options.shadows == ShadowMethod::kNone;
  if (args.compare_reference &&
      (host_refraction || (exact_shadows && asked_refraction == RefractionMethod::kNone)))
    fail(
        "--compare-reference measures a shadow or refraction method against the reference; with --shadows {} "
        "and --refraction {} there is nothing to measure",
        shadow_method_info(options.shadows).name, args.refraction);
  if (args.error_target && host_refraction)
    fail("--error-target chooses the grids of the device methods; --refraction {} has none", args.refraction);
  if (args.error_target && args.grids_given)
    fail("--error-target chooses --res and --shadow-res; leave them out");
  const bool tty = isatty(fileno(stderr)) && !args.quiet;

  std::future<PreparedRuntime<FrameRenderer>> background =
      prepare_in_background<FrameRenderer>(args.device, options);
  const auto load_start = Clock::now();
  if (tty) fmt::print(stderr, "\rreading {}...", args.input.empty() ? "the default scene" : args.input);
  Scene loaded = args.input.empty() ? default_scene() : load_input(args.input);
  const char* cr = tty ? "\r" : "";
  for (const MeshInstance& m : loaded.meshes)
    for (const std::string& w : m.warnings) fmt::print(stderr, "{}voxr: warning: {}\n", cr, w);
  for (const std::string& w : loaded.warnings) fmt::print(stderr, "{}voxr: warning: {}\n", cr, w);
  const bool animated = is_animated(loaded);
  const uint32_t width = size.x ? size.x : loaded.camera.width,
                 height = size.y ? size.y : loaded.camera.height;
  // Soup, camera, light, materials and environment (frame 0 of an animated scene).
  RenderCase c(std::move(loaded), width, height);
  const Scene& scene = c.scene();
  const std::vector<Material>& materials = c.materials();
  const EnvironmentMap& environment = c.environment();
  const TriangleSoup& soup = c.soup();
  // Without glass in the scene there is nothing to refract: no grid is built.
  if (!has_dielectric(soup, materials) && !host_refraction)
    options.refraction.method = RefractionMethod::kNone;
  const bool refracting = options.refraction.method != RefractionMethod::kNone;
  if (args.compare_reference && !refracting && exact_shadows)
    fail(
        "{}: --compare-reference has nothing to measure: the scene has no dielectric and --shadows {} is "
        "exact",
        scene.source, shadow_method_info(options.shadows).name);
  const Bounds bounds = soup.bounds();
  const CameraFrame& camera = c.camera();
  const RenderLight& light = c.light();
  const std::vector<RenderMaterial>& render_mats = c.render_materials();
  const double load_ms = ms_since(load_start);

  nlohmann::json report = {{"input", args.input.empty() ? "default scene" : args.input},
                           {"shadows", shadow_method_info(options.shadows).name},
                           {"refraction", refraction_method_info(options.refraction.method).name},
                           {"refraction_asked", refraction_method_info(asked_refraction).name},
                           {"environment", environment.source()},
                           {"triangles", soup.triangle_count()},
                           {"size", {width, height}},
                           {"animated", animated}};
  if (animated) report["fps"] = scene.fps;
  RenderedFrame last;  // the last frame (with --compare-reference its samples, transmittance and paths)
  std::vector<double> frame_ms;
  std::map<std::string, std::vector<double>> stage_ms;  // per stage, one per frame
  nlohmann::json frames = nlohmann::json::array();
  FrameStats stats;
  TechniqueDescription shadow_description, refraction_description;  // the device frame's techniques
  std::optional<RenderTargetChoice> target;
  FrameStats fixed_stats;  // --error-target: one frame on the fixed 512 grids it replaces
  // The frame's triangles: `soup` (frame 0, or every frame of a static scene) or `posed`.
  TriangleSoup posed;
  const TriangleSoup* current = &soup;
  // The exact reference of the frame's triangles, its BVH built on first need (the reference techniques,
  // image-space's d_N, --compare-reference).
  std::unique_ptr<EmbreeReference> posed_reference;
  const auto scene_reference = [&]() -> EmbreeReference& {
    if (current == &soup) return c.reference();
    if (!posed_reference) posed_reference = std::make_unique<EmbreeReference>(*current, materials);
    return *posed_reference;
  };
  const auto reference_scene = [&] { return &scene_reference().scene(); };
  // Poses frame f of an animated scene: the references' BVH of the old pose is dropped.
  const auto pose = [&](uint32_t f) {
    pose_scene(scene, f / scene.fps, soup.anchor, posed);
    current = &posed;
    posed_reference.reset();
  };
  const auto progress = [&](uint32_t f) {
    if (tty && args.frames > 1) fmt::print(stderr, "\r{:<60}\rframe {}/{}", "", f + 1, args.frames);
  };
  const auto finish_frame = [&](uint32_t f, double ms, double pose_ms, const nlohmann::json& stages) {
    frame_ms.push_back(ms);
    frames.push_back({{"time_s", animated ? f / scene.fps : 0.0},
                      {"frame_ms", ms},
                      {"pose_ms", pose_ms},
                      {"stages", stages}});
    if (pattern) write_image(last.image, pattern->name(f));
  };
  // Runs `frame` (which renders); a point light no light frame can hold (fit_light_frame) is named as the
  // scene file gives it.
  const auto placing_light = [&](auto&& frame) {
    try {
      return frame();
    } catch (const PlacementError& e) {
      const glm::dvec3 p = e.key() == "camera.position" ? scene.camera.position : scene.light.position;
      fail("{}: '{}' ({}, {}, {}) {}", scene.source, e.key(), p.x, p.y, p.z, e.reason());
    }
  };
  const auto wait_start = Clock::now();
  PreparedRuntime<FrameRenderer> prepared = background.get();
  const double wait_ms = ms_since(wait_start);
  if (tty) fmt::print(stderr, "\r{:<60}\r{}...", "", reference_only ? "tracing the reference" : "rendering");
  prepared.engine->set_environment(environment);
  // The scene's upload and the techniques' per-scene setup (image-space: Wyman's d_N, ray cast once per
  // scene as the paper precomputes it offline).
  double scene_setup_ms = 0.0;
  if (!animated) {
    const auto start = Clock::now();
    prepared.engine->set_scene(soup, materials, &scene_reference());
    scene_setup_ms = ms_since(start);
  }
  if (args.error_target) {
    // The grids are chosen on frame 0 (an animated scene's `soup` is its frame 0).
    if (animated) prepared.engine->set_scene(soup, materials, &scene_reference());
    target = placing_light([&] {
      return choose_render_grids(*prepared.engine, *reference_scene(), render_mats, light, environment,
                                 scene.camera, soup.anchor, bounds, width, height, *args.error_target,
                                 &options, [&](const std::string& line) {
                                   if (tty) fmt::print(stderr, "\r{:<60}\rerror target: {}", "", line);
                                 });
    });
    if (tty) fmt::print(stderr, "\r{:<60}\rrendering...", "");
  }
  for (uint32_t f = 0; f < args.frames; ++f) {
    progress(f);
    // Host posing, the upload and vertex normals and the techniques' per-scene setup (set_scene: e.g.
    // image-space refraction's d_N), and the exact shadows' BVH of the new pose.
    double pose_ms = 0.0;
    if (animated) {
      const auto pose_start = Clock::now();
      pose(f);
      prepared.engine->set_scene(posed, materials, &scene_reference());
      // The exact shadows' BVH is built while posing; a host-finished frame (the references) builds its
      // own inside the frame, where it is counted.
      if (options.shadows == ShadowMethod::kReference && !reference_only) reference_scene();
      pose_ms = ms_since(pose_start);
    }
    last = placing_light([&] { return prepared.engine->render(light, camera, options, &stats); });
    nlohmann::json frame_stages = nlohmann::json::object();
    for (const auto& [name, ms] : stats.stage_ms) {
      frame_stages[name] = ms;
      stage_ms[name].push_back(ms);
    }
    finish_frame(f, stats.frame_ms, pose_ms, frame_stages);
  }
  if (target) {
    // The saving is measured: the frame on the fixed grids, rendered twice (the first grows the buffers).
    RenderOptions fixed = options;
    fixed.keep_samples = false;
    if (target->refraction) fixed.refraction.resolution = kRenderTargetHighest;
    if (target->shadows) fixed.shadow_resolution = kRenderTargetHighest;
    for (int i = 0; i < 2; ++i)
      placing_light([&] { return prepared.engine->render(light, camera, fixed, &fixed_stats); });
  }
  nlohmann::json stages = nlohmann::json::object();
  for (const auto& [name, ms] : stage_ms) stages[name] = median(ms);
  // The references finish the frame on the host: the device only holds the scene.
  report["device"] = reference_only ? "host (Embree)" : prepared.cl->device().label();
  if (!reference_only) report["driver"] = prepared.cl->device().driver_version;
  report["ms"] = {{"stages", stages},
                  {"host", stats.host_ms},
                  {"runtime", prepared.runtime_ms},
                  {"programs", prepared.programs_ms},
                  {"wait", wait_ms}};
  if (!animated) report["ms"]["scene_setup"] = scene_setup_ms;
  report["host_syncs"] = stats.host_syncs;                  // waits for the device queue in the last frame
  report["capacity_rerenders"] = stats.capacity_rerenders;  // its tries made again (a count outgrew)
  shadow_description = prepared.engine->shadow_technique(options.shadows).describe(stats, options);
  refraction_description =
      prepared.engine->refraction_technique(options.refraction.method).describe(stats, options);
  report.update(shadow_description.report);
  report.update(refraction_description.report);
  if (args.profile) fmt::print("{}\n", prepared.cl->profiler().table());
  report["ms"]["load"] = load_ms;
  report["ms"]["frame"] = frame_ms.back();
  report["ms"]["frame_median"] = median(frame_ms);
  report["ms"]["frame_min"] = *std::min_element(frame_ms.begin(), frame_ms.end());
  report["ms"]["frame_max"] = *std::max_element(frame_ms.begin(), frame_ms.end());
  report["fps_rendered"] = 1000.0 / median(frame_ms);
  report["frame_count"] = args.frames;
  report["frames"] = frames;

  nlohmann::json compare = nlohmann::json::object();
  if (args.compare_reference) {
    // The exact transmittance at this frame's path ends: the shadows are measured with it, and the
    // refraction is measured on this frame's paths shaded with it, so that its error is refraction's alone.
    if (tty) fmt::print(stderr, "\r{:<60}\rtracing the exact shadows...", "");
    ReferenceFrame exact;
    exact.shadows = voxr::exact_shadows(*reference_scene(), last.samples, last.paths, render_mats, light,
                                        environment, width, height);
    double refraction_ms = 0.0;
    if (refracting) {
      if (tty) fmt::print(stderr, "\r{:<60}\rtracing the matched reference...", "");
      const auto ref_start = Clock::now();
      exact.refraction = render_refraction_reference(*reference_scene(), render_mats, light, environment,
                                                     camera, ReferenceModel::kMatched);
      refraction_ms = ms_since(ref_start);
    }
    if (tty) fmt::print(stderr, "\r{:<60}\rcomparing with the reference...", "");
    const auto compare_start = Clock::now();
    const FrameError error = measure_against_reference(last, exact);
    const double compare_ms = ms_since(compare_start);
    const ExactShadows& shadows = *exact.shadows;
    if (error.refraction) {
      const RefractionError& e = *error.refraction;
      const std::filesystem::path error_path = beside(last_output, "error");
      write_image(error_image(shadows.image, exact.refraction->image), error_path.string());
      compare["refraction"] = {{"reference", "matched"},
                               {"rmse", e.rmse},
                               {"psnr", finite_or_inf(e.psnr)},
                               {"shadows", "exact (the frame's paths, shaded with the exact transmittance)"},
                               {"angle_mean_deg", finite_or_inf(e.angle_mean_deg)},
                               {"angle_p95_deg", finite_or_inf(e.angle_p95_deg)},
                               {"angle_pixels", e.angle_pixels},
                               {"refracted_pixels", e.refracted_pixels},
                               {"lost_pixels", e.lost_pixels},
                               {"method_lost_pixels", e.method_lost_pixels},
                               // null when no pixel could be compared (the reference lost every one)
                               {"event_mismatch_share", std::isnan(e.event_mismatch_share)
                                                            ? nlohmann::json(nullptr)
                                                            : nlohmann::json(e.event_mismatch_share)},
                               {"nonfinite_pixels", e.nonfinite_pixels},
                               {"error_image", error_path.string()},
                               {"reference_ms", refraction_ms + compare_ms}};
    }
    if (!exact_shadows) {
      const ShadowError& e = *error.shadows;
      const std::filesystem::path error_path = beside(last_output, refracting ? "shadow-error" : "error");
      write_image(
          error_image(last.transmittance, shadows.transmittance, width, height, shadows.receivers, 1.0),
          error_path.string());
      compare["shadows"] = {{"transmittance_rmse", e.transmittance.rmse},
                            {"transmittance_max", e.transmittance.max_abs},
                            {"share_over_0.05", e.transmittance.share_over_threshold},
                            {"receivers", e.transmittance.receivers},
                            {"psnr", finite_or_inf(e.psnr)},
                            {"error_image", error_path.string()},
                            {"reference_ms", compare_ms}};
    }
  }
  if (!compare.empty()) report["compare_reference"] = compare;
  const uint64_t bytes = stats.device_bytes + stats.refraction_bytes;
  const uint64_t fixed_bytes = fixed_stats.device_bytes + fixed_stats.refraction_bytes;
  if (target) {
    const auto search_json = [](const ResolutionChoice& c, double budget) {
      nlohmann::json trials = nlohmann::json::array();
      for (const ResolutionTrial& t : c.trials) trials.push_back({{"res", t.resolution}, {"rmse", t.error}});
      return nlohmann::json{
          {"budget", budget}, {"met", c.met}, {"res", c.resolution}, {"rmse", c.error}, {"trials", trials}};
    };
    nlohmann::json t = {
        {"target", *args.error_target},
        {"measure", "image RMSE (linear RGB) against the Embree reference"},
        {"sample", {target->sample_width, target->sample_height}},
        {"sample_rmse", target->sample_error},
        {"search_ms", target->search_ms},
        {"device_bytes", bytes},
        {"fixed",
         {{"res", kRenderTargetHighest}, {"frame_ms", fixed_stats.frame_ms}, {"device_bytes", fixed_bytes}}}};
    if (target->refraction) t["refraction"] = search_json(*target->refraction, target->refraction_budget);
    if (target->shadows) t["shadows"] = search_json(*target->shadows, target->shadows_budget);
    report["error_target"] = t;
  }
  if (!pattern) write_image(last.image, args.output);
  report["ms"]["process"] = ms_since(process_start);
  if (!args.report.empty()) write_file_atomically(args.report, report.dump(2) + "\n");
  if (tty) fmt::print(stderr, "\r{:<60}\r", "");
  if (!args.quiet) {
    fmt::print("input      {} ({} triangles)\n", scene.source, soup.triangle_count());
    fmt::print("device     {}\n", report["device"].get<std::string>());
    fmt::print("shadows    {}{}\n", report["shadows"].get<std::string>(), shadow_description.suffix);
    fmt::print("refraction {}{}{}\n", report["refraction"].get<std::string>(), refraction_description.suffix,
               asked_refraction != options.refraction.method ? " (the scene has no dielectric)" : "");
    for (const std::string& line : shadow_description.lines) fmt::print("{}\n", line);
    for (const std::string& line : refraction_description.lines) fmt::print("{}\n", line);
    std::string stages;
    for (const auto& [name, ms] : stage_ms)
      if (median(ms) > 0.0)
        stages += fmt::format("{}{} {:.2f}", stages.empty() ? "" : ", ", name, median(ms));
    if (animated) {
      std::vector<double> pose_ms;
      for (const nlohmann::json& f : frames) pose_ms.push_back(f["pose_ms"].get<double>());
      fmt::print("animation  {} frames at {:g} fps, t = 0..{:.3f} s, posing ({}) median {:.2f} ms\n",
                 args.frames, scene.fps, (args.frames - 1) / scene.fps,
                 reference_only ? "host"
                 : options.shadows == ShadowMethod::kReference ||
                         options.refraction.method == RefractionMethod::kImageSpace
                     ? "host, upload, BVH"
                     : "host, upload",
                 median(pose_ms));
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
  add_size_option(*sub, args->size)->default_str("the scene camera's");
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
  return {sub, [args, sub] {
            check_method_flags(*args, *sub);
            args->grids_given = sub->count("--res") + sub->count("--shadow-res") > 0;
            return run_render(*args);
          }};
}

}  // namespace voxr::cli
