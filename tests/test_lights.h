// Lights for the light-frame tests: a unit-intensity directional or point light in anchor-relative
// coordinates (anchor 0), under the default environment's ambient.
#pragma once

#include <glm/glm.hpp>

#include "core/scene.h"
#include "render/render_scene.h"

namespace voxr::test {

inline RenderLight directional_light(glm::vec3 direction) {
  Light l;
  l.type = "directional";
  l.direction = direction;
  return render_light(l, kDefaultEnvironment, glm::dvec3(0.0));
}

inline RenderLight point_light(glm::vec3 position) {
  Light l;
  l.type = "point";
  l.position = position;
  return render_light(l, kDefaultEnvironment, glm::dvec3(0.0));
}

}  // namespace voxr::test
