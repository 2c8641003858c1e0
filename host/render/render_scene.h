// The scene's materials and light in the form the render kernels and the reference read (voxr_layout.h
// RenderMaterial, RenderLight): one conversion, used by every renderer.
#pragma once

#include <glm/glm.hpp>

#include <vector>

#include "core/scene.h"
#include "core/triangle_soup.h"
#include "voxr_layout.h"

namespace voxr {

// One RenderMaterial per scene material, same order (material ids index both).
std::vector<RenderMaterial> render_materials(const std::vector<Material>& materials);

// Whether a triangle of `soup` has a dielectric material (ids out of range are ignored): refraction has work.
bool has_dielectric(const TriangleSoup& soup, const std::vector<Material>& materials);

// The light with its position relative to `anchor` and `ambient` (the environment's mean radiance,
// EnvironmentMap::mean) as the ambient term.
// A directional light's direction is normalized. Throws voxr::Error for a zero direction.
RenderLight render_light(const Light& light, const glm::vec3& ambient, const glm::dvec3& anchor);

// Unit vector from `point` (anchor-relative) towards the light, and the irradiance the light gives there
// before shadowing (point: intensity / d^2, directional: intensity).
struct LightAtPoint {
  glm::vec3 to_light{0.0f};
  glm::vec3 irradiance{0.0f};
  float distance = 0.0f;  // to a point light; +inf for a directional one
};
LightAtPoint light_at(const RenderLight& light, const glm::vec3& point);

}  // namespace voxr
