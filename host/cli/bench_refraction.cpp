#include "cli/bench_refraction.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>

#include "cl/cl_runtime.h"
#include "cli/bench_support.h"
#include "cli/commands.h"
#include "cli/option_groups.h"
#include "cli/option_groups_render.h"
#include "cli/parse_args.h"
#include "cli/process.h"
#include "core/scene.h"
#include "eval/render_case.h"
#include "io/atomic_file.h"
#include "metrics/refraction_metrics.h"
#include "reference/reference_refraction.h"
#include "reference/reference_scene.h"
#include "render/environment_map.h"
#include "render/frame_renderer.h"
#include "render/render_scene.h"
#include "util/clock.h"
#include "util/error.h"
#include "util/median.h"

namespace voxr::cli {

namespace fs = std::filesystem;

namespace {

// Debian's python3, where python3-matplotlib is installed (a pyenv or venv python3 first on PATH may lack
// it).
constexpr const char* kSystemPython = "/usr/bin/python3";

// What the frame includes, said once in the Markdown.
constexpr const char* kFrameIncludes =
    "one whole frame: voxelize the scene with normals and materials (voxel methods; no inside channel: media "
    "are told by parity) + rasterize the camera's "
    "visibility + refract + the shadow method's light structure and lookup + shade + read the image back";

struct MethodCase {
  std::string label;  // as given: voxel-multi-dda-smooth, voxel-two, image-space, ...
  RefractionOptions options;
  bool grid = true;  // voxel methods: one case per resolution
};

const char* const kMethodHelp =
    "voxel-multi-STEP-NORMALS or voxel-two[-STEP-NORMALS] (STEP: dda or papers, NORMALS: smooth or voxel; "
    "voxel-two alone is the default papers-smooth), image-space, distance-maps (default layers and layer "
    "resolution)";

// Throws voxr::Error naming the method when it is none of kMethodHelp's forms.
MethodCase parse_method_case(const std::string& label) {
  MethodCase m{label, {}, true};
  const auto unknown = [&] { fail("bench refraction: unknown method '{}' (known: {})", label, kMethodHelp); };
  if (label == "image-space" || label == "distance-maps") {
    m.options.method =
        label == "image-space" ? RefractionMethod::kImageSpace : RefractionMethod::kDistanceMaps;
    m.grid = false;
    return m;
  }
  std::string rest;
  if (label.starts_with("voxel-multi")) {
    m.options.method = RefractionMethod::kVoxelMulti;
    rest = label.substr(11);
  } else if (label.starts_with("voxel-two")) {
    m.options.method = RefractionMethod::kVoxelTwo;
    rest = label.substr(9);
  } else {
    unknown();
  }
  // voxel-two alone: the defaults (RefractionOptions), as `voxr render` uses them.
  if (rest.empty() && m.options.method == RefractionMethod::kVoxelTwo) return m;
  // "-STEP-NORMALS"
  if (rest.size() < 2 || rest[0] != '-') unknown();
  const size_t dash = rest.find('-', 1);
  if (dash == std::string::npos) unknown();
  try {
    m.options.step = parse_step_rule(rest.substr(1, dash - 1));
    m.options.normals = parse_normal_kind(rest.substr(dash + 1));
  } catch (const Error&) {
    unknown();
  }
  return m;
}

using Row = RefractionBenchRow;

// What check_bench_refraction_args reads from the arguments.
struct CheckedArgs {
  std::vector<MethodCase> methods;
  ShadowMethod shadows = ShadowMethod::kNone;
  uint32_t width = 0, height = 0;
};

CheckedArgs check_args(const BenchRefractionArgs& args) {
  CheckedArgs c;
  for (const std::string& m : args.methods) c.methods.push_back(parse_method_case(m));
  if (c.methods.empty()) fail("bench refraction: no methods (--methods)");
  if (args.scenes.empty()) fail("bench refraction: no scenes (--scenes)");
  c.shadows = parse_shadow_method(args.shadows);
  const glm::uvec2 size = parse_size(args.size, "--size");
  c.width = size.x;
  c.height = size.y;
  for (const std::string& s : args.scenes) {
    std::error_code ec;
    if (!fs::exists(s, ec)) fail("{}: no such file", s);
  }
  return c;
}

std::string fmt_number(double v, int digits) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format("{:.{}f}", v, digits);
}

std::string res_text(uint32_t res) {
  return res ? std::to_string(res) : "";
}

}  // namespace

void check_bench_refraction_args(const BenchRefractionArgs& args) {
  check_args(args);
}

RefractionBenchRun measure_refraction(ClRuntime& cl, const BenchRefractionArgs& args) {
  const CheckedArgs checked = check_args(args);
  const std::vector<MethodCase>& methods = checked.methods;
  const ShadowMethod shadows = checked.shadows;
  const uint32_t width = checked.width, height = checked.height;
  const bool any_image_space = std::any_of(methods.begin(), methods.end(), [](const MethodCase& m) {
    return m.options.method == RefractionMethod::kImageSpace;
  });
  const bool tty = isatty(fileno(stderr));
  const auto progress = [&](const std::string& what) {
    if (tty) fmt::print(stderr, "\r{:<78}\r{}", "", what.substr(0, 78));
  };
  const auto progress_done = [&] {
    if (tty) fmt::print(stderr, "\r{:<78}\r", "");
  };

  RefractionBenchRun run;
  std::vector<Row>& rows = run.rows;
  std::string &fresh_table = run.fresh_table, &precompute_table = run.precompute_table;
  for (const std::string& scene_name : args.scenes) {
    const std::string label = scene_label(scene_name);
    progress(fmt::format("{}: reading", label));
    RenderCase c(load_input(scene_name), width, height);
    const std::vector<Material>& materials = c.materials();
    const EnvironmentMap& environment = c.environment();
    const TriangleSoup& soup = c.soup();
    const CameraFrame& camera = c.camera();
    const RenderLight& light = c.light();
    const std::vector<RenderMaterial>& render_mats = c.render_materials();
    progress_done();
    fmt::print("{}: {} triangles, {}x{}, load {}\n", label, soup.triangle_count(), width, height,
               load_average_text());
    std::fflush(stdout);

    // The matched reference, once: what every method is measured against, and Embree's frame.
    progress(fmt::format("{}: tracing the matched reference", label));
    const ReferenceScene& reference = c.reference().scene();
    const RefractionReference exact = render_refraction_reference(reference, render_mats, light, environment,
                                                                  camera, ReferenceModel::kMatched);
    {
      Row r;
      r.scene = label;
      r.method = "reference-matched";
      r.triangles = soup.triangle_count();
      r.frame_ms = exact.build_ms + exact.trace_ms + exact.shadow_ms + exact.shade_ms;
      r.frame_min = r.frame_max = r.frame_ms;
      r.error.psnr = std::numeric_limits<double>::infinity();
      rows.push_back(r);
      progress_done();
      fmt::print(
          "  reference-matched (BVH {:.1f} + trace {:.1f} + shadows {:.1f} + shade {:.1f}): {:.1f} ms\n",
          exact.build_ms, exact.trace_ms, exact.shadow_ms, exact.shade_ms, r.frame_ms);
      std::fflush(stdout);
    }
    FrameRenderer renderer(cl);
    renderer.set_environment(environment);
    if (any_image_space) {
      // image-space's per-scene setup (Wyman's d_N, ray cast) runs in set_scene once the technique is made.
      RenderOptions image_space;
      image_space.shadows = shadows;
      image_space.refraction.method = RefractionMethod::kImageSpace;
      renderer.prepare(image_space);
      progress(fmt::format("{}: ray casting d_N", label));
    }
    const auto scene_start = Clock::now();
    renderer.set_scene(soup, materials, &c.reference());
    if (any_image_space)
      precompute_table +=
          fmt::format("| {} | {} | {:.1f} |\n", label, soup.triangle_count(), ms_since(scene_start));

    for (const MethodCase& m : methods) {
      const std::vector<uint32_t> resolutions = m.grid ? args.resolutions : std::vector<uint32_t>{0};
      for (uint32_t res : resolutions) {
        progress(fmt::format("{}: {} {}", label, m.label, res_text(res)));
        RenderOptions o;
        o.shadows = shadows;
        o.shadow_resolution = args.shadow_res;
        o.refraction = m.options;
        if (res) o.refraction.resolution = res;
        renderer.prepare(o);
        for (int w = 0; w < args.warmup; ++w) renderer.render(light, camera, o);
        std::vector<double> ms, refraction_ms, layers_ms;
        FrameStats stats;
        for (int r = 0; r < args.repeat; ++r) {
          renderer.render(light, camera, o, &stats);
          ms.push_back(stats.frame_ms);
          double traced = 0.0;  // listing the pixels that see a dielectric and tracing them
          for (const char* stage : {"dielectric pixels", "refraction"})
            if (const auto it = stats.stage_ms.find(stage); it != stats.stage_ms.end()) traced += it->second;
          refraction_ms.push_back(traced);
          const auto layers = stats.stage_ms.find("dm-layers");
          layers_ms.push_back(layers == stats.stage_ms.end() ? 0.0 : layers->second);
        }
        // The error frame: the same refraction with the exact shadows, so the error is refraction's alone.
        RenderOptions e = o;
        e.shadows = ShadowMethod::kReference;
        e.keep_samples = true;
        renderer.prepare(e);
        const RenderedFrame frame = renderer.render(light, camera, e);
        Row row;
        row.scene = label;
        row.method = refraction_method_info(m.options.method).name;
        if (m.grid) {
          row.step = step_rule_info(m.options.step).name;
          row.normals = normal_kind_info(m.options.normals).name;
        }
        row.triangles = soup.triangle_count();
        row.resolution = res;
        row.frame_ms = median(ms);
        row.frame_min = *std::min_element(ms.begin(), ms.end());
        row.frame_max = *std::max_element(ms.begin(), ms.end());
        row.refraction_ms = median(refraction_ms);
        row.layers_ms = median(layers_ms);
        row.error = refraction_error(frame.image, frame.paths, exact.image, exact.paths);
        row.grid_bytes = stats.refraction_bytes;
        row.load = load_averages()[0];
        rows.push_back(row);
        progress_done();
        fmt::print(
            "  {:<26} {:>4}: {:8.2f} ms [{:.2f}, {:.2f}] refraction {:.2f} ms{}  RMSE {:.4f} PSNR {} angle "
            "{:.2f}/{:.2f} deg events {:.2f}% nonfinite {}  {:.2f} MiB (load {})\n",
            m.label, res_text(res), row.frame_ms, row.frame_min, row.frame_max, row.refraction_ms,
            row.layers_ms > 0.0 ? fmt::format(" dm-layers {:.2f} ms", row.layers_ms) : std::string(),
            row.error.rmse, fmt_number(row.error.psnr, 2), row.error.angle_mean_deg, row.error.angle_p95_deg,
            100.0 * row.error.event_mismatch_share, row.error.nonfinite_pixels,
            double(row.grid_bytes) / (1 << 20), load_average_text());
        std::fflush(stdout);
      }
    }

    // What a user gets: a fresh `voxr render` process.
    if (args.fresh > 0) {
      progress(fmt::format("{}: fresh processes", label));
      const std::vector<double> wall = time_fresh_renders(
          {scene_name, "--refraction", "voxel-multi", "--res", "256", "--shadows", args.shadows,
           "--shadow-res", std::to_string(args.shadow_res), "--size", args.size},
          args.fresh, args.device, "bench-refraction");
      fresh_table += fresh_table_row(label, soup.triangle_count(), wall);
      progress_done();
      fmt::print("  fresh `voxr render --refraction voxel-multi --res 256`: {:.0f} ms\n", median(wall));
      std::fflush(stdout);
    }
  }
  progress_done();
  return run;
}

int run_bench_refraction(const BenchRefractionArgs& args) {
  // Everything the command line says is checked before the device is opened.
  check_bench_refraction_args(args);
  const std::string load_before = load_average_text();
  ClRuntime cl(args.device);
  const std::string device = fmt::format("{} ({})", cl.device().name, cl.device().platform_name);
  const std::string driver = cl.device().driver_version;
  const std::string started = utc_now();
  fmt::print("device: {}, driver {}\n", device, driver);
  const RefractionBenchRun run = measure_refraction(cl, args);
  const std::vector<Row>& rows = run.rows;
  const std::string &fresh_table = run.fresh_table, &precompute_table = run.precompute_table;
  const std::string load_after = load_average_text();

  std::ostringstream csv;
  csv << "scene,triangles,method,step,normals,res,frame_ms,frame_ms_min,frame_ms_max,refraction_ms,dm_layers_"
         "ms,"
         "rmse,psnr,"
         "angle_mean_deg,angle_p95_deg,angle_pixels,event_mismatch,refracted_pixels,nonfinite,grid_bytes\n";
  for (const Row& r : rows)
    csv << fmt::format("{},{},{},{},{},{},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{},{},{},{},{},{},{},{},{}\n",
                       r.scene, r.triangles, r.method, r.step, r.normals, res_text(r.resolution), r.frame_ms,
                       r.frame_min, r.frame_max, r.refraction_ms, r.layers_ms, fmt_number(r.error.rmse, 6),
                       fmt_number(r.error.psnr, 3), fmt_number(r.error.angle_mean_deg, 4),
                       fmt_number(r.error.angle_p95_deg, 4), r.error.angle_pixels,
                       fmt_number(r.error.event_mismatch_share, 5), r.error.refracted_pixels,
                       r.error.nonfinite_pixels, r.grid_bytes);

  std::ostringstream md;
  md << fmt::format(
      "# voxr bench refraction\n\n"
      "- Device: {}, driver {}\n- Date: {}\n- Command: `{}`\n- Machine load (/proc/loadavg 1, 5, 15 min): "
      "{} before, {} after\n- Image {}, shadows {} at shadow resolution {}. Warm frames: median of {} after "
      "{} warm-up [min, max].\n\n",
      device, driver, started, command_line(), load_before, load_after, args.size,
      shadow_method_info(parse_shadow_method(args.shadows)).name, args.shadow_res, args.repeat, args.warmup);
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
        r.refraction_ms, r.layers_ms > 0.0 ? fmt_number(r.layers_ms, 2) : "-", fmt_number(r.error.rmse, 4),
        fmt_number(r.error.psnr, 2), fmt_number(r.error.angle_mean_deg, 2),
        fmt_number(r.error.angle_p95_deg, 2), fmt_number(100.0 * r.error.event_mismatch_share, 2),
        r.error.nonfinite_pixels, double(r.grid_bytes) / (1 << 20));
  }
  if (!precompute_table.empty())
    md << "\nImage-space's per-scene precompute, Wyman's d_N by ray casting (host, not in the frame):\n\n"
          "| scene | triangles | ms |\n|---|---:|---:|\n"
       << precompute_table;
  if (!fresh_table.empty())
    md << "\nFresh processes, `voxr render SCENE --refraction voxel-multi --res 256 --shadows "
       << args.shadows << " --shadow-res " << args.shadow_res << " --size " << args.size
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
  sub->add_option("--scenes", a->scenes, "scene files")->delimiter(',')->capture_default_str();
  sub->add_option("--methods", a->methods, kMethodHelp)->delimiter(',')->capture_default_str();
  add_grid_option(*sub, "--res", GridKind::kRefraction, a->resolutions);
  add_shadows_option(*sub, a->shadows, "the timed frames' shadow method (errors always use the exact ones)")
      ->capture_default_str();
  add_grid_option(*sub, "--shadow-res", GridKind::kShadow, a->shadow_res)->capture_default_str();
  add_size_option(*sub, a->size)->capture_default_str();
  add_device_option(*sub, a->device);
  add_out_prefix_option(*sub, a->out, "PREFIX.csv, PREFIX.md, PREFIX-charts/");
  add_repeat_options(*sub, a->repeat, a->warmup);
  add_fresh_option(*sub, a->fresh, "voxr render SCENE --refraction voxel-multi --res 256");
  return {sub, [a] { return run_bench_refraction(*a); }};
}

}  // namespace voxr::cli
