// voxr render [SCENE] -o out.png: one image of the scene with transparent shadows by the chosen method
// (render/frame_renderer.h; the Embree reference for --shadows reference), a summary of the light's grid and
// per-stage times, and with --compare-reference the error against the exact reference at the same receiver
// points (transmittance RMSE and maximum, share of pixels off by more than 0.05, image PSNR) and an error
// image beside the output.
//
// Like voxr voxelize, the device is opened and the programs built on a second thread while the scene is read.
#include <fmt/format.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>

#include "bench/median.h"
#include "cl/cl_runtime.h"
#include "cli/commands.h"
#include "cli/parse_args.h"
#include "cli/prepared_runtime.h"
#include "core/clock.h"
#include "core/default_scene.h"
#include "core/file_extension.h"
#include "core/scene.h"
#include "io/atomic_file.h"
#include "io/image_file.h"
#include "metrics/image_metrics.h"
#include "metrics/shadow_receivers.h"
#include "reference/reference_renderer.h"
#include "reference/reference_scene.h"
#include "render/environment_map.h"
#include "render/frame_renderer.h"
#include "render/render_scene.h"
#include "render/shade_host.h"

namespace voxr::cli {

namespace {

struct RenderArgs {
  std::string input;  // empty: the built-in default scene
  std::string output = "render.png";
  std::string shadows = "voxel";
  uint32_t shadow_res = 256;
  std::string mode;  // empty: center
  std::string size;  // empty: the scene camera's
  std::string device;
  std::string report;
  float bias = kDefaultShadowBias;
  float normal_offset = kDefaultNormalOffset;
  uint32_t frames = 1;
  bool compare_reference = false;
  bool profile = false;
  bool quiet = false;
};

// "out/a.png" -> "out/a.error.png"
std::filesystem::path beside(const std::string& output, const std::string& tag) {
  std::filesystem::path p(output);
  return p.parent_path() / (p.stem().string() + "." + tag + p.extension().string());
}

int run_render(const RenderArgs& args) {
  const auto process_start = Clock::now();
  RenderOptions options;
  options.shadows = parse_shadow_method(args.shadows);
  if (!args.mode.empty() && options.shadows != ShadowMethod::kVoxel)
    fail("--mode applies to --shadows voxel only (the light voxelizer's rule)");
  options.mode = parse_raster_mode(args.mode.empty() ? "center" : args.mode);
  options.shadow_resolution = args.shadow_res;
  options.bias = args.bias;
  options.normal_offset = args.normal_offset;
  options.keep_samples = args.compare_reference;
  if (!is_image_file(args.output))
    fail("{}: the image format is chosen by extension: .png or .exr", args.output);
  check_output_path(args.output);
  if (!args.report.empty()) check_output_path(args.report);
  const glm::uvec2 size =
      args.size.empty() ? glm::uvec2(0) : parse_size(args.size, "--size");  // 0: the camera's
  if (!args.input.empty()) {
    std::error_code ec;
    if (!std::filesystem::exists(args.input, ec)) fail("{}: no such file", args.input);
  }
  const bool reference_only = options.shadows == ShadowMethod::kReference;
  if (reference_only && args.compare_reference)
    fail(
        "--compare-reference measures a shadow method against the reference; --shadows reference is the "
        "reference itself");
  const bool tty = isatty(fileno(stderr)) && !args.quiet;

  std::future<PreparedRuntime<FrameRenderer>> background;
  if (!reference_only) background = prepare_in_background<FrameRenderer>(args.device, options);
  const auto load_start = Clock::now();
  if (tty) fmt::print(stderr, "\rreading {}...", args.input.empty() ? "the default scene" : args.input);
  Scene scene = args.input.empty() ? default_scene() : load_input(args.input);
  const char* cr = tty ? "\r" : "";
  for (const MeshInstance& m : scene.meshes)
    for (const std::string& w : m.warnings) fmt::print(stderr, "{}voxr: warning: {}\n", cr, w);
  const std::vector<Material> materials = scene.materials;
  const TriangleSoup soup = take_scene_triangles(scene);
  validate_soup(soup, scene.source);
  const Bounds bounds = soup.bounds();
  const uint32_t width = size.x ? size.x : scene.camera.width, height = size.y ? size.y : scene.camera.height;
  const CameraFrame camera = make_camera_frame(scene.camera, soup.anchor, bounds, width, height);
  const RenderLight light =
      render_light(scene.light, make_environment_map(scene.environment).mean(), soup.anchor);
  const std::vector<RenderMaterial> render_mats = render_materials(materials);
  const double load_ms = ms_since(load_start);

  nlohmann::json report = {{"input", args.input.empty() ? "default scene" : args.input},
                           {"shadows", shadow_method_info(options.shadows).name},
                           {"triangles", soup.triangle_count()},
                           {"size", {width, height}}};
  ImageRgba image;
  std::vector<SurfaceSample> samples;
  std::vector<glm::vec3> transmittance;
  std::vector<double> frame_ms;
  FrameStats stats;
  std::unique_ptr<ReferenceScene> reference;
  if (reference_only) {
    if (tty) fmt::print(stderr, "\r{:<60}\rtracing the reference...", "");
    reference = std::make_unique<ReferenceScene>(soup, materials);
    for (uint32_t f = 0; f < args.frames; ++f) {
      const auto frame_start = Clock::now();
      ReferenceRender r = render_reference(*reference, render_mats, light, camera);
      frame_ms.push_back(ms_since(frame_start) + (f == 0 ? reference->build_ms() : 0.0));
      image = std::move(r.image);
      report["ms"] = {{"bvh_build", r.build_ms},
                      {"primary", r.primary_ms},
                      {"shadow", r.shadow_ms},
                      {"shade", r.shade_ms}};
    }
    report["device"] = "host (Embree)";
  } else {
    const auto wait_start = Clock::now();
    PreparedRuntime<FrameRenderer> prepared = background.get();
    const double wait_ms = ms_since(wait_start);
    if (tty) fmt::print(stderr, "\r{:<60}\rrendering...", "");
    prepared.engine->set_scene(soup, materials);
    for (uint32_t f = 0; f < args.frames; ++f) {
      RenderedFrame frame = prepared.engine->render(light, camera, options, {}, &stats);
      frame_ms.push_back(stats.frame_ms);
      image = std::move(frame.image);
      samples = std::move(frame.samples);
      transmittance = std::move(frame.transmittance);
    }
    nlohmann::json stages = nlohmann::json::object();
    for (const auto& [name, ms] : stats.stage_ms) stages[name] = ms;
    report["device"] = prepared.cl->device().label();
    report["driver"] = prepared.cl->device().driver_version;
    report["ms"] = {{"stages", stages},
                    {"host", stats.host_ms},
                    {"runtime", prepared.runtime_ms},
                    {"programs", prepared.programs_ms},
                    {"wait", wait_ms}};
    if (options.shadows != ShadowMethod::kNone) {
      report["light_grid"] = {
          {"kind", stats.light.projective() ? "frustum" : "orthographic"},
          {"dims", {stats.light.grid.dims.x, stats.light.grid.dims.y, stats.light.grid.dims.z}},
          {"describe", stats.light.describe()},
          {"triangles", stats.light_triangles},
          {"device_bytes", stats.device_bytes}};
      if (options.shadows == ShadowMethod::kVoxel) report["mode"] = raster_mode_name(options.mode);
    }
    if (args.profile) fmt::print("{}\n", prepared.cl->profiler().table());
  }
  report["ms"]["load"] = load_ms;
  report["ms"]["frame"] = frame_ms.back();
  report["ms"]["frame_median"] = median(frame_ms);
  report["frames"] = args.frames;

  if (args.compare_reference && !reference_only) {
    if (tty) fmt::print(stderr, "\r{:<60}\rcomparing with the reference...", "");
    const auto ref_start = Clock::now();
    reference = std::make_unique<ReferenceScene>(soup, materials);
    const std::vector<glm::vec3> exact = reference_transmittance(*reference, light, samples);
    const std::vector<uint8_t> mask = shadow_receivers(samples, render_mats, light);
    const TransmittanceError e = transmittance_error(transmittance, exact, mask, 0.05);
    const ImageRgba exact_image = shade_samples(samples, exact, render_mats, light, width, height);
    const double p = psnr(image, exact_image);
    const std::filesystem::path error_path = beside(args.output, "error");
    write_image(error_image(transmittance, exact, width, height, mask, 1.0), error_path.string());
    report["compare_reference"] = {{"transmittance_rmse", e.rmse},
                                   {"transmittance_max", e.max_abs},
                                   {"share_over_0.05", e.share_over_threshold},
                                   {"receivers", e.receivers},
                                   {"psnr", std::isfinite(p) ? nlohmann::json(p) : nlohmann::json("inf")},
                                   {"error_image", error_path.string()},
                                   {"reference_ms", ms_since(ref_start)}};
  }
  write_image(image, args.output);
  report["ms"]["process"] = ms_since(process_start);
  if (!args.report.empty()) write_file_atomically(args.report, report.dump(2) + "\n");
  if (tty) fmt::print(stderr, "\r{:<60}\r", "");
  if (!args.quiet) {
    fmt::print("input      {} ({} triangles)\n", scene.source, soup.triangle_count());
    fmt::print("device     {}\n", report["device"].get<std::string>());
    fmt::print("shadows    {}", shadow_method_info(options.shadows).name);
    if (options.shadows == ShadowMethod::kVoxel) fmt::print(" ({} mode)", raster_mode_name(options.mode));
    fmt::print("\n");
    if (report.contains("light_grid"))
      fmt::print("light grid {}, {} triangles from the light, {:.1f} MiB\n", stats.light.describe(),
                 stats.light_triangles, double(stats.device_bytes) / (1 << 20));
    std::string stages;
    for (const auto& [name, ms] : stats.stage_ms)
      if (ms > 0.0) stages += fmt::format("{}{} {:.2f}", stages.empty() ? "" : ", ", name, ms);
    fmt::print("frame      {:.2f} ms{} (median of {} frame{}; min {:.2f}, max {:.2f})\n", median(frame_ms),
               reference_only ? " incl. the BVH build on the first" : "", frame_ms.size(),
               frame_ms.size() == 1 ? "" : "s", *std::min_element(frame_ms.begin(), frame_ms.end()),
               *std::max_element(frame_ms.begin(), frame_ms.end()));
    if (!stages.empty()) fmt::print("stages ms  {} (host {:.2f})\n", stages, stats.host_ms);
    if (report.contains("compare_reference")) {
      const auto& c = report["compare_reference"];
      fmt::print(
          "vs exact   transmittance RMSE {:.4f}, max {:.3f}, {:.2f}% of {} receivers off by > 0.05, "
          "PSNR {} dB\n",
          c["transmittance_rmse"].get<double>(), c["transmittance_max"].get<double>(),
          100.0 * c["share_over_0.05"].get<double>(), c["receivers"].get<uint64_t>(),
          c["psnr"].is_number() ? fmt::format("{:.2f}", c["psnr"].get<double>()) : "inf");
      fmt::print("wrote      {}\n", c["error_image"].get<std::string>());
    }
    fmt::print("process ms {:.1f}\n", report["ms"]["process"].get<double>());
    fmt::print("wrote      {}\n", args.output);
  }
  return 0;
}

}  // namespace

Command add_render(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* sub = app.add_subcommand("render", "Render a scene with transparent shadows (.png or .exr)");
  sub->add_option("input", args->input, "scene file (.json) or mesh; omitted: the built-in default scene");
  sub->add_option("-o,--output", args->output, "image: .png (8-bit sRGB) or .exr (linear float)")
      ->capture_default_str();
  std::string methods;
  for (const ShadowMethodInfo& info : kShadowMethods)
    methods += fmt::format("{}{} ({})", methods.empty() ? "" : "; ", info.name, info.summary);
  sub->add_option("--shadows", args->shadows, methods)->capture_default_str();
  sub->add_option("--shadow-res", args->shadow_res,
                  "columns along the longer side of the light's grid, and its slabs (voxel, uniform, filter, "
                  "opaque)")
      ->check(CLI::Range(3u, 4096u))
      ->capture_default_str();
  sub->add_option("--mode", args->mode,
                  "voxel: center (default; each column's write count is its centre ray's crossings) or "
                  "conservative (over-counts)");
  sub->add_option("--size", args->size, "image WIDTHxHEIGHT (default: the scene camera's)");
  sub->add_option("--bias", args->bias, "slabs (or depth-map texels) receivers move towards the light")
      ->check(CLI::Range(0.0f, 64.0f))
      ->capture_default_str();
  sub->add_option("--normal-offset", args->normal_offset, "columns receivers move off their surface")
      ->check(CLI::Range(0.0f, 64.0f))
      ->capture_default_str();
  sub->add_option("--frames", args->frames,
                  "render the frame this many times in this process and report the median (warm) frame time")
      ->check(CLI::Range(1u, 100000u))
      ->capture_default_str();
  sub->add_flag("--compare-reference", args->compare_reference,
                "measure the shadows against the Embree reference at the same receivers; writes "
                "OUT.error.png");
  sub->add_option("--device", args->device, "OpenCL device P:D or name substring (also $VOXR_DEVICE)");
  sub->add_option("--report", args->report, "write a JSON report (times, light grid, errors)");
  sub->add_flag("--profile", args->profile, "print a per-kernel time table");
  sub->add_flag("-q,--quiet", args->quiet, "print nothing but errors");
  return {sub, [args] { return run_render(*args); }};
}

}  // namespace voxr::cli
