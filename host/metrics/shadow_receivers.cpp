#include "metrics/shadow_receivers.h"

#include "render/render_scene.h"

namespace voxr {

std::vector<uint8_t> shadow_receivers(std::span<const SurfaceSample> samples,
                                      std::span<const RenderMaterial> materials, const RenderLight& light) {
  std::vector<uint8_t> mask(samples.size(), 0);
  for (size_t i = 0; i < samples.size(); ++i) {
    const SurfaceSample& s = samples[i];
    if (s.triangle == VOXR_NO_TRIANGLE || s.material >= materials.size()) continue;
    if (materials[s.material].kind == VOXR_MATERIAL_DIELECTRIC) continue;
    const glm::vec3 p(s.position[0], s.position[1], s.position[2]);
    const glm::vec3 n(s.normal[0], s.normal[1], s.normal[2]);
    mask[i] = glm::dot(n, light_at(light, p).to_light) > 0.0f ? 1 : 0;
  }
  return mask;
}

}  // namespace voxr
