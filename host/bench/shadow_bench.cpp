#include "bench/shadow_bench.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "bench/report_fields.h"
#include "core/default_scene.h"
#include "core/scene.h"
#include "eval/reference_comparison.h"
#include "eval/render_case.h"
#include "reference/reference_scene.h"
#include "render/frame_renderer.h"
#include "util/clock.h"
#include "util/error.h"
#include "util/median.h"

namespace voxr {

namespace {

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

}  // namespace

ShadowBenchRun measure_shadows(ClRuntime& cl, const ShadowBenchOptions& options, const FreshRenders& fresh) {
  const uint32_t width = options.size.x, height = options.size.y;
  std::vector<MethodCase> methods;
  for (const std::string& m : options.methods) methods.push_back(parse_method_case(m));

  ShadowBenchRun run;
  std::vector<Row>& rows = run.rows;
  for (const std::string& scene_name : options.scenes) {
    RenderCase c(scene_name == "default" ? default_scene() : load_input(scene_name), width, height);
    const std::vector<Material>& materials = c.materials();
    const TriangleSoup& soup = c.soup();
    const CameraFrame& camera = c.camera();
    const RenderLight& light = c.light();
    const std::string label = scene_label(scene_name);
    fmt::print("{}: {} triangles, {}x{}, load {:.2f}\n", label, soup.triangle_count(), width, height,
               load_averages()[0]);
    std::fflush(stdout);

    FrameRenderer renderer(cl);
    renderer.set_scene(soup, materials, &c.reference());
    // The exact shadows at the camera's samples, and what they cost Embree per frame (a BVH rebuild each).
    RenderOptions first;
    first.shadows = ShadowMethod::kNone;
    first.keep_samples = true;
    renderer.prepare(first);
    const RenderedFrame base = renderer.render(light, camera, first);
    std::vector<double> ref_ms;
    ReferenceFrame exact;
    for (int r = 0; r < std::max(1, options.repeat / 2); ++r) {
      const auto start = Clock::now();
      ReferenceScene reference(soup, materials);
      exact.shadows = exact_shadows(reference, base.samples, {}, c.render_materials(), light, c.environment(),
                                    width, height);
      ref_ms.push_back(ms_since(start));
    }
    const std::vector<uint8_t>& mask = exact.shadows->receivers;
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
      for (uint32_t res : options.resolutions) {
        RenderOptions o = m.options;
        o.shadow_resolution = res;
        renderer.prepare(o);
        for (int w = 0; w < options.warmup; ++w) renderer.render(light, camera, o);
        std::vector<double> ms;
        FrameStats stats;
        for (int r = 0; r < options.repeat; ++r) {
          renderer.render(light, camera, o, &stats);
          ms.push_back(stats.frame_ms);
        }
        o.keep_samples = true;
        const FrameError error = measure_against_reference(renderer.render(light, camera, o), exact);
        Row row;
        row.scene = label;
        row.method = shadow_method_info(o.shadows).name;
        row.mode = o.shadows == ShadowMethod::kVoxel ? raster_mode_name(o.mode) : "-";
        row.resolution = res;
        row.frame_ms = median(ms);
        row.frame_min = *std::min_element(ms.begin(), ms.end());
        row.frame_max = *std::max_element(ms.begin(), ms.end());
        row.error = error.shadows->transmittance;
        row.psnr = error.shadows->psnr;
        // voxel-exact has no light grid: its triangle grid, --res voxels along the scene's longest side.
        row.light_grid = o.shadows == ShadowMethod::kVoxelExact
                             ? fmt::format("triangle grid, {} voxels on the scene's longest side", res)
                             : stats.light.describe();
        row.device_bytes = stats.device_bytes;
        row.triangles = soup.triangle_count();
        row.load = load_averages()[0];
        rows.push_back(row);
        fmt::print(
            "  {:<18} {:>4}: {:8.2f} ms [{:.2f}, {:.2f}]  RMSE {:.4f} max {:.3f} >0.05 {:.2f}%  PSNR {} "
            "({}; load {:.2f})\n",
            m.label, res, row.frame_ms, row.frame_min, row.frame_max, row.error.rmse, row.error.max_abs,
            100.0 * row.error.share_over_threshold, number_cell(row.psnr, 2), row.light_grid, row.load);
        std::fflush(stdout);
      }
    }

    // What a user gets: a fresh `voxr render` process.
    if (fresh) {
      std::vector<std::string> render_args = {"--shadows", "voxel", "--shadow-res", "256"};
      if (scene_name != "default") render_args.insert(render_args.begin(), scene_name);
      FreshRenderTimes t{label, soup.triangle_count(), fresh(render_args)};
      fmt::print("  fresh `voxr render --shadows voxel --shadow-res 256`: {:.0f} ms\n", median(t.wall_ms));
      run.fresh.push_back(std::move(t));
    }
  }
  return run;
}

}  // namespace voxr
