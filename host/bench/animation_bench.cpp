#include "bench/animation_bench.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>

#include "bench/report_fields.h"
#include "core/animation.h"
#include "core/scene.h"
#include "render/environment_map.h"
#include "render/frame_renderer.h"
#include "render/render_scene.h"
#include "util/clock.h"
#include "util/error.h"
#include "util/median.h"

namespace voxr {

std::string stage_text(const std::map<std::string, double>& stages, const char* separator) {
  std::string out;
  for (const auto& [name, ms] : stages)
    if (ms > 0.0) out += fmt::format("{}{} {:.2f}", out.empty() ? "" : separator, name, ms);
  return out;
}

std::vector<AnimationBenchRow> measure_animation(ClRuntime& cl, const AnimationBenchOptions& options,
                                                 const FreshRenders& fresh) {
  const glm::uvec2 size = options.size;
  std::vector<AnimationBenchRow> rows;
  for (const std::string& scene_name : options.scenes) {
    const Scene scene = load_input(scene_name);
    if (!is_animated(scene)) fail("{}: the scene is not animated (no mesh has an \"animation\")", scene_name);
    const std::vector<Material>& materials = scene.materials;
    const TriangleSoup rest = scene_triangles(scene);
    validate_soup(rest, scene.source);
    const CameraFrame camera = make_camera_frame(scene.camera, rest.anchor, rest.bounds(), size.x, size.y);
    const RenderLight light =
        render_light(scene.light, make_environment_map(scene.environment).mean(), rest.anchor);
    RenderOptions render;  // voxel shadows, centre mode, 256 columns
    render.refraction.method =
        has_dielectric(rest, materials) ? RefractionMethod::kVoxelMulti : RefractionMethod::kNone;
    FrameRenderer renderer(cl);
    renderer.prepare(render);
    renderer.set_environment(make_environment_map(scene.environment));

    AnimationBenchRow row;
    row.scene = scene_label(scene_name);
    row.refraction = refraction_method_info(render.refraction.method).name;
    row.triangles = rest.triangle_count();
    row.fps_scene = scene.fps;
    std::vector<double> frame_ms, pose_ms;
    std::map<std::string, std::vector<double>> stage_ms;
    TriangleSoup posed;
    for (int f = 0; f < options.frames; ++f) {
      const auto pose_start = Clock::now();
      pose_scene(scene, f / scene.fps, rest.anchor, posed);
      renderer.set_scene(posed, materials);
      pose_ms.push_back(ms_since(pose_start));
      FrameStats stats;
      renderer.render(light, camera, render, &stats);
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
        row.scene, row.triangles, options.frames, row.refraction, row.frame_ms, row.frame_min, row.frame_max,
        1000.0 / row.frame_ms, row.pose_ms, stage_text(row.stages, ", "), load_averages()[0]);
    std::fflush(stdout);
    if (fresh) {
      row.fresh_ms = median(fresh({scene_name, "--frames", std::to_string(options.frames)}));
      fmt::print("  fresh `voxr render --frames {}`: {:.0f} ms\n", options.frames, row.fresh_ms);
    }
    rows.push_back(row);
  }
  return rows;
}

}  // namespace voxr
