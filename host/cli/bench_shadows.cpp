#include "cli/bench_shadows.h"

#include <fmt/format.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cl/cl_runtime.h"
#include "cli/bench_support.h"
#include "cli/commands.h"
#include "cli/option_groups.h"
#include "cli/parse_args.h"
#include "cli/process.h"
#include "core/default_scene.h"
#include "core/scene.h"
#include "eval/render_case.h"
#include "io/atomic_file.h"
#include "metrics/image_metrics.h"
#include "metrics/shadow_receivers.h"
#include "reference/reference_scene.h"
#include "render/environment_map.h"
#include "render/frame_renderer.h"
#include "render/render_scene.h"
#include "render/shade_host.h"
#include "util/clock.h"
#include "util/median.h"

namespace voxr::cli {

namespace fs = std::filesystem;

namespace {

// Debian's python3, where python3-matplotlib is installed (a pyenv or venv python3 first on PATH may lack
// it).
constexpr const char* kSystemPython = "/usr/bin/python3";

struct MethodCase {
  std::string label;  // voxel-center, uniform, ...
  RenderOptions options;
};

MethodCase parse_method_case(const std::string& label) {
  MethodCase m{label, {}};
  if (label == "voxel-center" || label == "voxel") {
    m.options.shadows = ShadowMethod::kVoxel;
    m.options.mode = RasterMode::kCenter;
  } else if (label == "voxel-conservative") {
    m.options.shadows = ShadowMethod::kVoxel;
    m.options.mode = RasterMode::kConservative;
  } else {
    m.options.shadows = parse_shadow_method(label);
    if (m.options.shadows == ShadowMethod::kReference || m.options.shadows == ShadowMethod::kNone)
      fail("bench shadows: '{}' is measured in every run (reference) or has no shadows (none)", label);
  }
  return m;
}

using Row = ShadowBenchRow;

std::string fmt_psnr(double p) {
  return std::isfinite(p) ? fmt::format("{:.2f}", p) : "inf";
}

}  // namespace

ShadowBenchRun measure_shadows(ClRuntime& cl, const BenchShadowsArgs& args) {
  const glm::uvec2 size = parse_size(args.size, "--size");
  const uint32_t width = size.x, height = size.y;
  std::vector<MethodCase> methods;
  for (const std::string& m : args.methods) methods.push_back(parse_method_case(m));

  ShadowBenchRun run;
  std::vector<Row>& rows = run.rows;
  std::string& fresh_table = run.fresh_table;
  for (const std::string& scene_name : args.scenes) {
    RenderCase c(scene_name == "default" ? default_scene() : load_input(scene_name), width, height);
    const std::vector<Material>& materials = c.materials();
    const TriangleSoup& soup = c.soup();
    const CameraFrame& camera = c.camera();
    const RenderLight& light = c.light();
    const std::vector<RenderMaterial>& render_mats = c.render_materials();
    const std::string label = scene_label(scene_name);
    fmt::print("{}: {} triangles, {}x{}, load {:.2f}\n", label, soup.triangle_count(), width, height,
               load_averages()[0]);
    std::fflush(stdout);

    FrameRenderer renderer(cl);
    renderer.set_scene(soup, materials, &c.reference());
    // The exact transmittance at the camera's samples, and what it costs Embree per frame.
    RenderOptions first;
    first.shadows = ShadowMethod::kNone;
    first.keep_samples = true;
    renderer.prepare(first);
    const RenderedFrame base = renderer.render(light, camera, first);
    std::vector<double> ref_ms;
    std::vector<glm::vec3> exact;
    ImageRgba exact_image;
    for (int r = 0; r < std::max(1, args.repeat / 2); ++r) {
      const auto start = Clock::now();
      ReferenceScene reference(soup, materials);
      exact = reference.transmittance(light, base.samples);
      exact_image = shade_samples(base.samples, exact, render_mats, light, width, height);
      ref_ms.push_back(ms_since(start));
    }
    const std::vector<uint8_t> mask = shadow_receivers(base.samples, render_mats, light);
    {
      Row r;
      r.scene = label;
      r.method = "reference";
      r.mode = "embree";
      r.frame_ms = median(ref_ms);
      r.frame_min = *std::min_element(ref_ms.begin(), ref_ms.end());
      r.frame_max = *std::max_element(ref_ms.begin(), ref_ms.end());
      r.error.receivers = std::count(mask.begin(), mask.end(), uint8_t(1));
      r.psnr = std::numeric_limits<double>::infinity();
      r.triangles = soup.triangle_count();
      r.light_grid = "BVH rebuild + shadow rays, host";
      rows.push_back(r);
      fmt::print("  reference (BVH build + shadow rays): {:.1f} ms [{:.1f}, {:.1f}]\n", r.frame_ms,
                 r.frame_min, r.frame_max);
    }

    for (const MethodCase& m : methods) {
      for (uint32_t res : args.resolutions) {
        RenderOptions o = m.options;
        o.shadow_resolution = res;
        renderer.prepare(o);
        for (int w = 0; w < args.warmup; ++w) renderer.render(light, camera, o);
        std::vector<double> ms;
        FrameStats stats;
        for (int r = 0; r < args.repeat; ++r) {
          renderer.render(light, camera, o, &stats);
          ms.push_back(stats.frame_ms);
        }
        o.keep_samples = true;
        const RenderedFrame frame = renderer.render(light, camera, o);
        Row row;
        row.scene = label;
        row.method = shadow_method_info(o.shadows).name;
        row.mode = o.shadows == ShadowMethod::kVoxel ? raster_mode_name(o.mode) : "-";
        row.resolution = res;
        row.frame_ms = median(ms);
        row.frame_min = *std::min_element(ms.begin(), ms.end());
        row.frame_max = *std::max_element(ms.begin(), ms.end());
        row.error = transmittance_error(frame.transmittance, exact, mask, 0.05);
        row.psnr = psnr(frame.image, exact_image);
        row.light_grid = stats.light.describe();
        row.device_bytes = stats.device_bytes;
        row.triangles = soup.triangle_count();
        row.load = load_averages()[0];
        rows.push_back(row);
        fmt::print(
            "  {:<18} {:>4}: {:8.2f} ms [{:.2f}, {:.2f}]  RMSE {:.4f} max {:.3f} >0.05 {:.2f}%  PSNR {} "
            "({}; load {:.2f})\n",
            m.label, res, row.frame_ms, row.frame_min, row.frame_max, row.error.rmse, row.error.max_abs,
            100.0 * row.error.share_over_threshold, fmt_psnr(row.psnr), row.light_grid, row.load);
        std::fflush(stdout);
      }
    }

    // What a user gets: a fresh `voxr render` process.
    if (args.fresh > 0) {
      std::vector<std::string> render_args = {"--shadows", "voxel",  "--shadow-res",
                                              "256",       "--size", args.size};
      if (scene_name != "default") render_args.insert(render_args.begin(), scene_name);
      const std::vector<double> wall =
          time_fresh_renders(render_args, args.fresh, args.device, "bench-shadows");
      fresh_table += fresh_table_row(label, soup.triangle_count(), wall);
      fmt::print("  fresh `voxr render --shadows voxel --shadow-res 256`: {:.0f} ms\n", median(wall));
    }
  }
  return run;
}

int run_bench_shadows(const BenchShadowsArgs& args) {
  ClRuntime cl(args.device);
  const std::string device = fmt::format("{} ({}, driver {})", cl.device().name, cl.device().platform_name,
                                         cl.device().driver_version);
  fmt::print("device: {}\n", device);
  const ShadowBenchRun run = measure_shadows(cl, args);
  const std::vector<Row>& rows = run.rows;
  const std::string& fresh_table = run.fresh_table;

  std::ostringstream csv;
  csv << "scene,method,mode,resolution,frame_ms,frame_ms_min,frame_ms_max,rmse,max_abs,share_over_0.05,psnr,"
         "receivers,triangles,device_bytes,light_grid\n";
  for (const Row& r : rows)
    csv << fmt::format("{},{},{},{},{:.3f},{:.3f},{:.3f},{:.5f},{:.4f},{:.5f},{},{},{},{},\"{}\"\n", r.scene,
                       r.method, r.mode, r.resolution, r.frame_ms, r.frame_min, r.frame_max, r.error.rmse,
                       r.error.max_abs, r.error.share_over_threshold, fmt_psnr(r.psnr), r.error.receivers,
                       r.triangles, r.device_bytes, r.light_grid);
  std::ostringstream md;
  md << fmt::format(
      "# voxr bench shadows\n\nDevice: {}. Image {}. Warm frames: median of {} after {} warm-up "
      "[min, max], wall time of one whole frame read back to the host. Errors at the visible "
      "receivers against Embree's exact transmittance at the same points.\n\n",
      device, args.size, args.repeat, args.warmup);
  md << "| scene | method | mode | res | frame ms | [min, max] | T RMSE | T max | > 0.05 | PSNR dB | light "
        "grid |\n"
        "|---|---|---|---:|---:|---|---:|---:|---:|---:|---|\n";
  for (const Row& r : rows)
    md << fmt::format(
        "| {} | {} | {} | {} | {:.2f} | [{:.2f}, {:.2f}] | {:.4f} | {:.3f} | {:.2f}% | {} | {} |\n", r.scene,
        r.method, r.mode, r.resolution ? std::to_string(r.resolution) : "-", r.frame_ms, r.frame_min,
        r.frame_max, r.error.rmse, r.error.max_abs, 100.0 * r.error.share_over_threshold, fmt_psnr(r.psnr),
        r.light_grid);
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
  sh->add_option("--scenes", shadows->scenes, "scene files (default: the built-in scene)")
      ->delimiter(',')
      ->capture_default_str();
  add_grid_option(*sh, "--res", GridKind::kShadow, shadows->resolutions);
  sh->add_option("--methods", shadows->methods, "voxel-center, voxel-conservative, uniform, filter, opaque")
      ->delimiter(',')
      ->capture_default_str();
  add_size_option(*sh, shadows->size)->capture_default_str();
  add_device_option(*sh, shadows->device);
  add_out_prefix_option(*sh, shadows->out, "PREFIX.csv, PREFIX.md, PREFIX-charts/");
  add_repeat_options(*sh, shadows->repeat, shadows->warmup);
  add_fresh_option(*sh, shadows->fresh, "voxr render SCENE --shadows voxel --shadow-res 256");
  return {sh, [shadows] { return run_bench_shadows(*shadows); }};
}

}  // namespace voxr::cli
