// One "measure against the reference" (DESIGN.md eval/): the exact frame of a case at a camera, computed
// once, and the error of any frame rendered there against it, as one typed record. `voxr render
// --compare-reference`, `bench shadows|refraction` (and so `bench pareto`), the `--error-target` search and
// the rendering stability cases all measure with it; the numbers themselves are metrics/' (image_metrics.h,
// refraction_metrics.h, shadow_receivers.h).
//
// The exact frame has up to two parts:
//   shadows     Embree's exact transmittance at a frame's camera samples (its path ends), the receivers a
//               shadow metric counts there, and those samples shaded with it: the frame as it would be with
//               exact shadows, so that a frame's difference from it is its shadows' alone;
//   refraction  the matched refraction reference (reference_refraction.h): its image and paths.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "eval/render_case.h"
#include "metrics/image_metrics.h"
#include "metrics/refraction_metrics.h"
#include "reference/reference_refraction.h"
#include "reference/reference_scene.h"
#include "render/environment_map.h"
#include "render/frame_renderer.h"
#include "util/image_rgba.h"
#include "voxr_layout.h"

namespace voxr {

// The exact shadows at one frame's samples (exact_shadows). Where only images are compared (the
// --error-target search) the image may be a device frame rendered with ShadowMethod::kReference instead, the
// other two left empty.
struct ExactShadows {
  std::vector<glm::vec3> transmittance;  // per pixel, to the light (1 where the sample has no triangle)
  std::vector<uint8_t> receivers;        // per pixel: 1 where a shadow metric counts (shadow_receivers)
  ImageRgba image;                       // the samples shaded with `transmittance`
};

// Traces the exact transmittance at `samples` (width * height, e.g. RenderedFrame::samples of a keep_samples
// frame) and shades them: along `paths` (shade_paths: the frame's refraction kept, its shadows exact) when
// given, else the samples themselves (shade_samples: the primary visibility, shaded flat where a dielectric
// is seen). Throws voxr::Error when a span's length is not width * height.
ExactShadows exact_shadows(const ReferenceScene& scene, std::span<const SurfaceSample> samples,
                           std::span<const RefractionPath> paths,
                           const std::vector<RenderMaterial>& materials, const RenderLight& light,
                           const EnvironmentMap& environment, uint32_t width, uint32_t height);

// The exact shadows of a render case's own frame: `renderer` (its scene set to c's soup and materials)
// renders c's camera without shadows, keeping the samples, and exact_shadows traces the transmittance at them
// (the samples shaded flat where a dielectric is seen). Used where shadows alone are measured (the stability
// suite's shadow cases, tests); `primary`, when given, receives that frame. Throws what FrameRenderer::render
// and exact_shadows throw.
ExactShadows case_exact_shadows(FrameRenderer& renderer, RenderCase& c, RenderedFrame* primary = nullptr);

// The exact frame a case's frames are measured against; either part may be absent.
struct ReferenceFrame {
  std::optional<ExactShadows> shadows;
  std::optional<RefractionReference> refraction;  // the matched model

  // The image a frame's image is compared with as a whole: the refraction reference's when there is one,
  // else the shadows'. Throws voxr::Error when the frame has neither part.
  const ImageRgba& image() const;
};

// A frame's shadows against the exact ones.
struct ShadowError {
  TransmittanceError transmittance;  // the frame's transmittance at the receivers (transmittance_error)
  double psnr = 0.0;                 // dB: the frame's image against ExactShadows::image (+inf when equal)
};

// How far a frame is from the exact frame. Each part is there when both the reference and the frame have
// what it reads.
struct FrameError {
  double image_rmse = 0.0, image_psnr = 0.0;  // the frame's image against ReferenceFrame::image()
  // reference.shadows and the frame's transmittance (keep_samples)
  std::optional<ShadowError> shadows;
  // reference.refraction and the frame's paths (keep_samples): the frame's paths with exact shadows against
  // the matched reference (refraction_error). With reference.shadows the image measured is
  // ExactShadows::image (the frame's own paths shaded with the exact transmittance: exact_shadows was given
  // the frame's paths); without, the frame's image, which the caller renders with exact shadows
  // (ShadowMethod::kReference).
  std::optional<RefractionError> refraction;
};

// Measures `frame` against `reference`; `threshold` is transmittance_error's. Throws voxr::Error when sizes
// differ or the reference has no part.
FrameError measure_against_reference(const RenderedFrame& frame, const ReferenceFrame& reference,
                                     double threshold = 0.05);

}  // namespace voxr
