// voxr::render (include/voxr/render.h): RenderSettings -> RenderJob, run_render_job (eval/render_job.h, the
// function `voxr render` runs), the image as floats and the report as text. The checks CLI11 makes on the
// flags (ranges, method-only flags) are made here with the flags' names, as the CLI words them.
#include "voxr/render.h"

#include <fmt/format.h>

#include <cstring>

#include "cli/option_groups.h"
#include "eval/render_job.h"
#include "render/distance_map_refraction.h"
#include "util/error.h"

namespace voxr {

namespace {

template <typename T>
void check_range(const char* flag, T value, T lo, T hi) {
  if (!(value >= lo && value <= hi)) fail("{} {}: out of range {}..{}", flag, value, lo, hi);
}

RenderJob render_job(const RenderSettings& s) {
  const RenderJob defaults;
  RenderJob job;
  job.input = s.scene;
  job.shadows = s.shadows;
  job.refraction = s.refraction;
  if (s.width != 0 || s.height != 0) {
    check_range("--size width", s.width, 1u, 16384u);
    check_range("--size height", s.height, 1u, 16384u);
  }
  job.size = {s.width, s.height};
  job.device = s.device;
  check_range("--shadow-res", s.shadow_res, cli::kShadowResMin, cli::kShadowResMax);
  check_range("--res", s.res, cli::kRefractionResMin, cli::kRefractionResMax);
  job.shadow_res = s.shadow_res;
  job.res = s.res;
  job.grids_given = s.res != defaults.res || s.shadow_res != defaults.shadow_res;
  job.mode = s.mode;
  check_range("--bias", s.bias, 0.0f, 64.0f);
  check_range("--normal-offset", s.normal_offset, 0.0f, 64.0f);
  job.bias = s.bias;
  job.normal_offset = s.normal_offset;
  job.refraction_grid = s.refraction_grid;
  check_range("--coarse-res", s.coarse_res, 0u, cli::kRefractionResMax);
  job.coarse_res = s.coarse_res;
  job.step = s.step;
  job.normals = s.normals;
  check_range("--angle-threshold", s.angle_threshold, 0.0f, 180.0f);
  job.angle_threshold = s.angle_threshold;
  const uint32_t dm_depth = s.dm_depth == 0 ? defaults.dm_depth : s.dm_depth;
  check_range("--layers", s.layers, 1u, kDistanceMapMaxLayers);
  check_range("--layer-res", s.layer_res, kDistanceMapMinRes, kDistanceMapMaxRes);
  check_range("--dm-depth", dm_depth, 1u, uint32_t(VOXR_PATH_MAX_EVENTS));
  // The CLI refuses these flags with another method when given; here: when changed from the default.
  if (s.refraction != "distance-maps") {
    if (s.layers != defaults.layers)
      fail("--layers applies to --refraction distance-maps only, not --refraction {}", s.refraction);
    if (s.layer_res != defaults.layer_res)
      fail("--layer-res applies to --refraction distance-maps only, not --refraction {}", s.refraction);
    if (dm_depth != defaults.dm_depth)
      fail("--dm-depth applies to --refraction distance-maps only, not --refraction {}", s.refraction);
  }
  job.layers = s.layers;
  job.layer_res = s.layer_res;
  job.dm_depth = dm_depth;
  check_range("--frames", s.frames, 1u, 100000u);
  job.frames = s.frames;
  if (s.error_target) check_range("--error-target", *s.error_target, 0.0, 1.0);
  job.error_target = s.error_target;
  job.compare_reference = s.compare_reference;
  return job;
}

}  // namespace

RenderedImage render(const RenderSettings& settings) {
  RenderedImage out;
  RenderJobHooks hooks;
  hooks.warning = [&](const std::string& w) { out.warnings.push_back(w); };
  RenderJobResult r = run_render_job(render_job(settings), hooks);
  out.width = r.image.width;
  out.height = r.image.height;
  // glm::vec4 is four packed floats: one copy into the public type (16 bytes a pixel).
  static_assert(sizeof(glm::vec4) == 4 * sizeof(float));
  out.rgba.resize(r.image.pixels.size() * 4);
  if (!out.rgba.empty()) std::memcpy(out.rgba.data(), r.image.pixels.data(), out.rgba.size() * sizeof(float));
  out.report_json = r.report.dump(2);
  return out;
}

}  // namespace voxr
