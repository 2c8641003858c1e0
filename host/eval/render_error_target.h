// voxr render --error-target E: the smallest grids whose frame lies within E of the Embree reference, image
// RMSE in linear RGB, measured on a sample of the pixels: the frame rendered at half the width and half the
// height (a regular quarter of the pixels), against the reference traced once at that size.
//   refraction grid (voxel-multi, voxel-two): the frame with exact shadows at its path ends against the
//            matched reference (reference_refraction.h), so that the error is refraction's alone; with a
//            shadow grid to choose too it must meet kRefractionShare of E (errors of the two add roughly in
//            quadrature: 0.8 E leaves 0.6 E for the shadows);
//   shadow grid (voxel, uniform, filter, opaque): the whole frame at the chosen refraction grid against the
//            reference (without refraction: the same visibility buffer shaded with the exact transmittance).
// Each search is core/resolution_search.h over 16..512 (the fixed grid the saving is measured against is
// 512); the chosen frame's error on the sample is measured once more and reported.
#pragma once

#include <optional>
#include <vector>

#include "core/resolution_search.h"
#include "core/scene.h"
#include "reference/reference_scene.h"
#include "render/environment_map.h"
#include "render/frame_renderer.h"

namespace voxr {

struct RenderTargetChoice {
  std::optional<ResolutionChoice> refraction, shadows;  // absent: that part has no grid or is exact
  double refraction_budget = 0.0, shadows_budget = 0.0;
  double sample_error = 0.0;  // the chosen grids' frame on the sample against the reference
  uint32_t sample_width = 0, sample_height = 0;
  double search_ms = 0.0;
};

inline constexpr uint32_t kRenderTargetLowest = 16, kRenderTargetHighest = 512;
inline constexpr double kRefractionShare = 0.8;

// Chooses options->refraction.resolution and options->shadow_resolution (those with a grid) and returns the
// search. `renderer` has the scene and environment set. Throws voxr::Error when neither has a grid.
RenderTargetChoice choose_render_grids(FrameRenderer& renderer, const ReferenceScene& reference,
                                       const std::vector<RenderMaterial>& materials, const RenderLight& light,
                                       const EnvironmentMap& environment, const Camera& camera,
                                       const glm::dvec3& anchor, const Bounds& bounds, uint32_t width,
                                       uint32_t height, double target, RenderOptions* options,
                                       const std::function<void(const std::string&)>& progress);

}  // namespace voxr
