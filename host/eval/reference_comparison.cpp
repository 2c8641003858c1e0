#include "eval/reference_comparison.h"

#include <utility>

#include "metrics/shadow_receivers.h"
#include "reference/reference_renderer.h"
#include "render/shade_host.h"
#include "util/error.h"

namespace voxr {

ExactShadows exact_shadows(const ReferenceScene& scene, std::span<const SurfaceSample> samples,
                           std::span<const RefractionPath> paths,
                           const std::vector<RenderMaterial>& materials, const RenderLight& light,
                           const EnvironmentMap& environment, uint32_t width, uint32_t height) {
  ExactShadows s;
  s.transmittance = reference_transmittance(scene, light, samples);
  s.receivers = shadow_receivers(samples, materials, light);
  s.image = paths.empty()
                ? shade_samples(samples, s.transmittance, materials, light, width, height)
                : shade_paths(samples, s.transmittance, paths, materials, light, environment, width, height);
  return s;
}

ExactShadows case_exact_shadows(FrameRenderer& renderer, RenderCase& c, RenderedFrame* primary) {
  RenderOptions o;
  o.shadows = ShadowMethod::kNone;
  o.keep_samples = true;
  renderer.prepare(o);
  RenderedFrame frame = renderer.render(c.light(), c.camera(), o);
  ExactShadows exact = exact_shadows(c.reference().scene(), frame.samples, {}, c.render_materials(),
                                     c.light(), c.environment(), c.camera().width, c.camera().height);
  if (primary) *primary = std::move(frame);
  return exact;
}

const ImageRgba& ReferenceFrame::image() const {
  if (refraction) return refraction->image;
  if (shadows) return shadows->image;
  fail("measure against the reference: the exact frame has neither shadows nor refraction");
}

FrameError measure_against_reference(const RenderedFrame& frame, const ReferenceFrame& reference,
                                     double threshold) {
  FrameError e;
  const ImageRgba& exact = reference.image();
  e.image_rmse = rmse(frame.image, exact);
  e.image_psnr = psnr(frame.image, exact);
  if (reference.shadows && !frame.transmittance.empty())
    e.shadows = ShadowError{transmittance_error(frame.transmittance, reference.shadows->transmittance,
                                                reference.shadows->receivers, threshold),
                            psnr(frame.image, reference.shadows->image)};
  if (reference.refraction && !frame.paths.empty())
    e.refraction = refraction_error(reference.shadows ? reference.shadows->image : frame.image, frame.paths,
                                    reference.refraction->image, reference.refraction->paths);
  return e;
}

}  // namespace voxr
