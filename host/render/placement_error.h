// PlacementError: a light or camera a method cannot work from where the scene puts it.
#pragma once

#include <glm/vec3.hpp>
#include <string>

#include "util/error.h"

namespace voxr {

// A scene object a method cannot use where it stands: a point light among or beside the receivers
// (fit_light_frame), the camera inside a dielectric (distance maps). what() names `key` and the position
// anchor-relative; key() is the scene file's key ("light.position", "camera.position") and reason() the rest
// of the sentence ("lies among the receivers: ..."), for callers that know the scene to name the file and
// the position as the user wrote it (cmd_render).
class PlacementError : public Error {
 public:
  PlacementError(std::string key, const glm::vec3& position, std::string reason);
  const std::string& key() const { return key_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string key_;
  std::string reason_;
};

}  // namespace voxr
