#include "bench/refraction_bench.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "bench/report_fields.h"
#include "core/scene.h"
#include "eval/reference_comparison.h"
#include "eval/render_case.h"
#include "reference/reference_refraction.h"
#include "render/environment_map.h"
#include "render/frame_renderer.h"
#include "render/refraction_method.h"
#include "render/render_scene.h"
#include "util/clock.h"
#include "util/error.h"
#include "util/median.h"

namespace voxr {

namespace fs = std::filesystem;

namespace {

struct MethodCase {
  std::string label;  // as given: voxel-multi-dda-smooth, voxel-two, image-space, ...
  RefractionOptions options;
  bool grid = true;  // voxel methods: one case per resolution
};

// Throws voxr::Error naming the method when it is none of kMethodHelp's forms.
MethodCase parse_method_case(const std::string& label) {
  MethodCase m{label, {}, true};
  const auto unknown = [&] {
    fail("bench refraction: unknown method '{}' (known: {})", label, kRefractionBenchMethodHelp);
  };
  if (label == "image-space" || label == "distance-maps") {
    m.options.method =
        label == "image-space" ? RefractionMethod::kImageSpace : RefractionMethod::kDistanceMaps;
    m.grid = false;
    return m;
  }
  if (label == "voxel-exact") {  // one case per resolution: the grid of its triangle lists
    m.options.method = RefractionMethod::kVoxelExact;
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
};

CheckedArgs check_args(const RefractionBenchOptions& args) {
  CheckedArgs c;
  for (const std::string& m : args.methods) c.methods.push_back(parse_method_case(m));
  if (c.methods.empty()) fail("bench refraction: no methods (--methods)");
  if (args.scenes.empty()) fail("bench refraction: no scenes (--scenes)");
  c.shadows = parse_shadow_method(args.shadows);
  for (const std::string& s : args.scenes) {
    std::error_code ec;
    if (!fs::exists(s, ec)) fail("{}: no such file", s);
  }
  return c;
}

}  // namespace

const char* const kRefractionBenchMethodHelp =
    "voxel-multi-STEP-NORMALS or voxel-two[-STEP-NORMALS] (STEP: dda or papers, NORMALS: smooth or voxel; "
    "voxel-two alone is the default papers-smooth), voxel-exact, image-space, distance-maps (default layers "
    "and layer resolution)";

void check_refraction_bench(const RefractionBenchOptions& options) {
  check_args(options);
}

RefractionBenchRun measure_refraction(ClRuntime& cl, const RefractionBenchOptions& args,
                                      const FreshRenders& fresh) {
  const CheckedArgs checked = check_args(args);
  const std::vector<MethodCase>& methods = checked.methods;
  const ShadowMethod shadows = checked.shadows;
  const uint32_t width = args.size.x, height = args.size.y;
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
    ReferenceFrame reference;
    reference.refraction = render_refraction_reference(c.reference().scene(), render_mats, light, environment,
                                                       camera, ReferenceModel::kMatched);
    const RefractionReference& exact = *reference.refraction;
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
    if (any_image_space) run.precompute.push_back({label, soup.triangle_count(), ms_since(scene_start)});

    for (const MethodCase& m : methods) {
      const std::vector<uint32_t> resolutions = m.grid ? args.resolutions : std::vector<uint32_t>{0};
      for (uint32_t res : resolutions) {
        progress(fmt::format("{}: {} {}", label, m.label, resolution_cell(res)));
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
        const FrameError error = measure_against_reference(renderer.render(light, camera, e), reference);
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
        row.error = *error.refraction;
        row.grid_bytes = stats.refraction_bytes;
        row.load = load_averages()[0];
        rows.push_back(row);
        progress_done();
        fmt::print(
            "  {:<26} {:>4}: {:8.2f} ms [{:.2f}, {:.2f}] refraction {:.2f} ms{}  RMSE {:.4f} PSNR {} angle "
            "{:.2f}/{:.2f} deg events {:.2f}% nonfinite {}  {:.2f} MiB (load {})\n",
            m.label, resolution_cell(res), row.frame_ms, row.frame_min, row.frame_max, row.refraction_ms,
            row.layers_ms > 0.0 ? fmt::format(" dm-layers {:.2f} ms", row.layers_ms) : std::string(),
            row.error.rmse, number_cell(row.error.psnr, 2), row.error.angle_mean_deg, row.error.angle_p95_deg,
            100.0 * row.error.event_mismatch_share, row.error.nonfinite_pixels,
            double(row.grid_bytes) / (1 << 20), load_average_text());
        std::fflush(stdout);
      }
    }

    // What a user gets: a fresh `voxr render` process.
    if (fresh) {
      progress(fmt::format("{}: fresh processes", label));
      const std::string method(refraction_method_info(kDefaultRefractionMethod).name);
      FreshRenderTimes t{label, soup.triangle_count(),
                         fresh({scene_name, "--refraction", method, "--res", "256", "--shadows", args.shadows,
                                "--shadow-res", std::to_string(args.shadow_res)})};
      progress_done();
      fmt::print("  fresh `voxr render --refraction {} --res 256`: {:.0f} ms\n", method, median(t.wall_ms));
      std::fflush(stdout);
      run.fresh.push_back(std::move(t));
    }
  }
  progress_done();
  return run;
}

}  // namespace voxr
