// Which pixels a shadow metric counts (DESIGN.md "Metrics": shadows are measured at receiver points): those
// whose sample shows an opaque or sheet surface lit from the side the viewer sees (n . l > 0), where the
// transmittance changes the image. Dielectrics (shaded flat), the background and the light's far side are
// left out.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "voxr_layout.h"

namespace voxr {

// One flag per sample: 1 for a visible receiver. Material ids index `materials`.
std::vector<uint8_t> shadow_receivers(std::span<const SurfaceSample> samples,
                                      std::span<const RenderMaterial> materials, const RenderLight& light);

}  // namespace voxr
