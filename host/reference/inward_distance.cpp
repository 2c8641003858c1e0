#include "reference/inward_distance.h"

#include "core/error.h"

namespace voxr {

// Placeholder until the reference branch lands.
std::vector<float> inward_distances(const ReferenceScene&, const TriangleSoup&, const std::vector<glm::vec3>&) {
  fail("inward distances are not built yet");
}

}  // namespace voxr
