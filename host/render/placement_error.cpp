#include "render/placement_error.h"

#include <fmt/format.h>

#include <utility>

namespace voxr {

PlacementError::PlacementError(std::string key, const glm::vec3& position, std::string reason)
    : Error(fmt::format("'{}' ({:.4g}, {:.4g}, {:.4g}) (anchor-relative) {}", key, position.x, position.y,
                        position.z, reason)),
      key_(std::move(key)),
      reason_(std::move(reason)) {}

}  // namespace voxr
