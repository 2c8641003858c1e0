#include "render/render_scene.h"

#include <limits>

#include "util/error.h"

namespace voxr {

std::vector<RenderMaterial> render_materials(const std::vector<Material>& materials) {
  std::vector<RenderMaterial> out;
  out.reserve(materials.size());
  for (const Material& m : materials) {
    RenderMaterial r{};
    for (int c = 0; c < 3; ++c) {
      r.color[c] = m.color[c];
      r.transmittance[c] = m.transmittance[c];
      r.absorption[c] = m.absorption[c];
    }
    r.kind = m.kind == MaterialKind::kOpaque       ? VOXR_MATERIAL_OPAQUE
             : m.kind == MaterialKind::kDielectric ? VOXR_MATERIAL_DIELECTRIC
                                                   : VOXR_MATERIAL_SHEET;
    r.ior = m.ior;
    out.push_back(r);
  }
  return out;
}

RenderLight render_light(const Light& light, const glm::vec3& ambient, const glm::dvec3& anchor) {
  RenderLight r{};
  r.directional = light.type == "directional" ? 1u : 0u;
  const glm::vec3 position(glm::dvec3(light.position) - anchor);
  glm::vec3 direction = light.direction;
  if (r.directional) {
    if (!(glm::length(direction) > 0.0f))
      throw Error("light: a directional light needs a non-zero direction");
    direction = glm::normalize(direction);
  }
  for (int c = 0; c < 3; ++c) {
    r.position[c] = position[c];
    r.direction[c] = direction[c];
    r.intensity[c] = light.intensity[c];
    r.ambient[c] = ambient[c];
  }
  return r;
}

LightAtPoint light_at(const RenderLight& light, const glm::vec3& point) {
  LightAtPoint out;
  const glm::vec3 intensity(light.intensity[0], light.intensity[1], light.intensity[2]);
  if (light.directional) {
    out.to_light = -glm::vec3(light.direction[0], light.direction[1], light.direction[2]);
    out.irradiance = intensity;
    out.distance = std::numeric_limits<float>::infinity();
  } else {
    const glm::vec3 d = glm::vec3(light.position[0], light.position[1], light.position[2]) - point;
    out.distance = glm::length(d);
    out.to_light = out.distance > 0.0f ? d / out.distance : glm::vec3(0.0f);
    out.irradiance = out.distance > 0.0f ? intensity / (out.distance * out.distance) : glm::vec3(0.0f);
  }
  return out;
}

bool has_dielectric(const TriangleSoup& soup, const std::vector<Material>& materials) {
  for (const glm::uvec4& t : soup.triangles)
    if (t.w < materials.size() && materials[t.w].kind == MaterialKind::kDielectric) return true;
  return false;
}

}  // namespace voxr
