#include "reference/reference_refraction.h"

#include "core/error.h"

namespace voxr {

// Placeholder until the reference branch lands.
RefractionReference render_refraction_reference(const ReferenceScene&, const std::vector<RenderMaterial>&,
                                                const RenderLight&, const EnvironmentMap&, const CameraFrame&,
                                                ReferenceModel, uint32_t) {
  fail("the refraction reference is not built yet");
}

}  // namespace voxr
