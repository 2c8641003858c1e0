// run_render_job: `voxr render` between its flags and its files (render_job.h). Like voxr voxelize, the
// device is opened and the programs built on a second thread while the scene is read.
//
// Frames: an animated scene (core/animation.h) is posed at t = f / fps for frame f and handed to the renderer
// again (re-voxelized on the device: nothing is precomputed; the references rebuild their BVH every frame,
// image-space refraction ray casts d_N every frame); the camera and light stay those of frame 0. A static
// scene renders the same frame N times (warm timing). --compare-reference measures the last frame against
// the exact reference: for refraction, image RMSE/PSNR against the matched reference, exit direction error,
// event-sequence mismatches and non-finite pixels; without refraction, the shadows' transmittance at the same
// receiver points (RMSE, maximum, share off by more than 0.05, image PSNR).
#include "eval/render_job.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <future>
#include <memory>

#include "cl/cl_runtime.h"
#include "cl/prepared_runtime.h"
#include "core/animation.h"
#include "core/default_scene.h"
#include "core/scene.h"
#include "eval/reference_comparison.h"
#include "eval/render_case.h"
#include "io/image_file.h"
#include "metrics/image_metrics.h"
#include "metrics/refraction_metrics.h"
#include "reference/reference_refraction.h"
#include "render/environment_map.h"
#include "render/frame_renderer.h"
#include "render/light_frame.h"
#include "render/placement_error.h"
#include "render/render_scene.h"
#include "util/clock.h"
#include "util/error.h"
#include "util/median.h"

namespace voxr {

namespace {

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

}  // namespace

RenderOptions render_job_options(const RenderJob& args) {
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

RenderJobResult run_render_job(const RenderJob& args, const RenderJobHooks& hooks) {
  const auto process_start = Clock::now();
  RenderJobResult result;
  RenderOptions options = render_job_options(args);
  const glm::uvec2 size = args.size;  // 0: the camera's
  if (args.frames == 0) fail("--frames must be at least 1");
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
  const auto status = [&](const std::string& line) {
    if (hooks.status) hooks.status(line);
  };

  std::future<PreparedRuntime<FrameRenderer>> background =
      prepare_in_background<FrameRenderer>(args.device, options);
  const auto load_start = Clock::now();
  status(fmt::format("reading {}...", args.input.empty() ? "the default scene" : args.input));
  Scene loaded = args.input.empty() ? default_scene() : load_input(args.input);
  if (hooks.warning) {
    for (const MeshInstance& m : loaded.meshes)
      for (const std::string& w : m.warnings) hooks.warning(w);
    for (const std::string& w : loaded.warnings) hooks.warning(w);
  }
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
    if (args.frames > 1) status(fmt::format("frame {}/{}", f + 1, args.frames));
  };
  const auto finish_frame = [&](uint32_t f, double ms, double pose_ms, const nlohmann::json& stages) {
    frame_ms.push_back(ms);
    frames.push_back({{"time_s", animated ? f / scene.fps : 0.0},
                      {"frame_ms", ms},
                      {"pose_ms", pose_ms},
                      {"stages", stages}});
    if (hooks.frame) hooks.frame(f, last.image);
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
  status(reference_only ? "tracing the reference..." : "rendering...");
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
                                 &options, [&](const std::string& line) { status("error target: " + line); });
    });
    status("rendering...");
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
  if (args.profile) result.profile_table = prepared.cl->profiler().table();
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
    status("tracing the exact shadows...");
    ReferenceFrame exact;
    exact.shadows = voxr::exact_shadows(*reference_scene(), last.samples, last.paths, render_mats, light,
                                        environment, width, height);
    double refraction_ms = 0.0;
    if (refracting) {
      status("tracing the matched reference...");
      const auto ref_start = Clock::now();
      exact.refraction = render_refraction_reference(*reference_scene(), render_mats, light, environment,
                                                     camera, ReferenceModel::kMatched);
      refraction_ms = ms_since(ref_start);
    }
    status("comparing with the reference...");
    const auto compare_start = Clock::now();
    const FrameError error = measure_against_reference(last, exact);
    const double compare_ms = ms_since(compare_start);
    const ExactShadows& shadows = *exact.shadows;
    if (error.refraction) {
      const RefractionError& e = *error.refraction;
      const bool write_error = !hooks.error_images_beside.empty();
      const std::filesystem::path error_path = beside(hooks.error_images_beside, "error");
      if (write_error) write_image(error_image(shadows.image, exact.refraction->image), error_path.string());
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
      if (!write_error) compare["refraction"].erase("error_image");
    }
    if (!exact_shadows) {
      const ShadowError& e = *error.shadows;
      const bool write_error = !hooks.error_images_beside.empty();
      const std::filesystem::path error_path =
          beside(hooks.error_images_beside, refracting ? "shadow-error" : "error");
      if (write_error)
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
      if (!write_error) compare["shadows"].erase("error_image");
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
  report["ms"]["process"] = ms_since(process_start);
  result.image = std::move(last.image);
  result.report = std::move(report);
  result.source = scene.source;
  result.triangles = soup.triangle_count();
  result.reference_only = reference_only;
  result.animated = animated;
  result.fps = scene.fps;
  result.options = options;
  result.asked_refraction = asked_refraction;
  result.shadow_description = std::move(shadow_description);
  result.refraction_description = std::move(refraction_description);
  result.stats = std::move(stats);
  result.frame_ms = std::move(frame_ms);
  for (const nlohmann::json& f : frames) result.pose_ms.push_back(f["pose_ms"].get<double>());
  result.stage_ms = std::move(stage_ms);
  result.target = std::move(target);
  result.fixed_stats = std::move(fixed_stats);
  return result;
}

}  // namespace voxr
