#include "eval/render_error_target.h"

#include <fmt/format.h>

#include <algorithm>

#include "eval/reference_comparison.h"
#include "reference/reference_refraction.h"
#include "util/clock.h"
#include "util/error.h"

namespace voxr {

RenderTargetChoice choose_render_grids(FrameRenderer& renderer, const ReferenceScene& reference,
                                       const std::vector<RenderMaterial>& materials, const RenderLight& light,
                                       const EnvironmentMap& environment, const Camera& camera,
                                       const glm::dvec3& anchor, const Bounds& bounds, uint32_t width,
                                       uint32_t height, double target, RenderOptions* options,
                                       const std::function<void(const std::string&)>& progress) {
  const auto start = Clock::now();
  const bool refraction_grid = is_voxel_refraction(options->refraction.method);
  const bool refracting = options->refraction.method != RefractionMethod::kNone;
  // voxel-exact's grid changes its speed, not its error (it is exact at any): --shadow-res sets it.
  const bool shadow_grid = options->shadows != ShadowMethod::kReference &&
                           options->shadows != ShadowMethod::kNone &&
                           options->shadows != ShadowMethod::kVoxelExact;
  if (!refraction_grid && !shadow_grid)
    fail(
        "--error-target chooses the grids of voxel refraction and of the shadow method; with --refraction {} "
        "and --shadows {} there is none",
        refraction_method_info(options->refraction.method).name, shadow_method_info(options->shadows).name);
  RenderTargetChoice choice;
  choice.sample_width = std::max(1u, width / 2);
  choice.sample_height = std::max(1u, height / 2);
  const CameraFrame sample =
      make_camera_frame(camera, anchor, bounds, choice.sample_width, choice.sample_height);
  const auto frame = [&](const RenderOptions& o) { return renderer.render(light, sample, o); };
  // The exact frame on the sample: the matched refraction reference, or without refraction the device frame
  // with exact shadows (the same visibility buffer: the shadows' error alone). Frames are measured by their
  // image alone (FrameError::image_rmse).
  RenderOptions exact_shadows = *options;
  exact_shadows.shadows = ShadowMethod::kReference;
  exact_shadows.keep_samples = false;
  ReferenceFrame exact;
  if (refracting)
    exact.refraction = render_refraction_reference(reference, materials, light, environment, sample,
                                                   ReferenceModel::kMatched);
  else
    exact.shadows = ExactShadows{{}, {}, frame(exact_shadows).image};
  const auto error = [&](const RenderOptions& o) {
    return measure_against_reference(frame(o), exact).image_rmse;
  };
  if (refraction_grid) {
    choice.refraction_budget = shadow_grid ? kRefractionShare * target : target;
    choice.refraction = choose_resolution(choice.refraction_budget, kRenderTargetLowest, kRenderTargetHighest,
                                          [&](uint32_t r) {
                                            RenderOptions o = exact_shadows;
                                            o.refraction.resolution = r;
                                            const double e = error(o);
                                            progress(fmt::format("refraction grid {} -> {:.5f}", r, e));
                                            return e;
                                          });
    options->refraction.resolution = choice.refraction->resolution;
    exact_shadows.refraction.resolution = choice.refraction->resolution;
  }
  if (shadow_grid) {
    choice.shadows_budget = target;
    choice.shadows =
        choose_resolution(choice.shadows_budget, kRenderTargetLowest, kRenderTargetHighest, [&](uint32_t r) {
          RenderOptions o = *options;
          o.keep_samples = false;
          o.shadow_resolution = r;
          const double e = error(o);
          progress(fmt::format("shadow grid {} -> {:.5f}", r, e));
          return e;
        });
    options->shadow_resolution = choice.shadows->resolution;
  }
  RenderOptions chosen = *options;
  chosen.keep_samples = false;
  choice.sample_error = error(chosen);
  choice.search_ms = ms_since(start);
  return choice;
}

}  // namespace voxr
