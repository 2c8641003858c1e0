#include "metrics/refraction_metrics.h"

#include "core/error.h"

namespace voxr {

// Placeholder until the reference branch lands.
RefractionError refraction_error(const ImageRgba&, std::span<const RefractionPath>, const ImageRgba&,
                                 std::span<const RefractionPath>) {
  fail("refraction metrics are not built yet");
}

}  // namespace voxr
