#include "render/shade_host.h"

#include "core/error.h"
#include "render/render_scene.h"
#include "shading.h"

namespace voxr {

ImageRgba shade_samples(std::span<const SurfaceSample> samples, std::span<const glm::vec3> transmittance,
                        const std::vector<RenderMaterial>& materials, const RenderLight& light,
                        uint32_t width, uint32_t height) {
  const size_t pixels = size_t(width) * height;
  if (samples.size() != pixels || transmittance.size() != pixels)
    fail("shade_samples: {} samples and {} transmittances for a {}x{} image", samples.size(),
         transmittance.size(), width, height);
  ImageRgba image(width, height);
  for (size_t i = 0; i < pixels; ++i) {
    const SurfaceSample& s = samples[i];
    glm::vec4& out = image.pixels[i];
    out.w = 1.0f;
    if (s.triangle == VOXR_NO_TRIANGLE) {
      for (int c = 0; c < 3; ++c) out[c] = light.ambient[c];
      continue;
    }
    if (s.material >= materials.size())
      fail("shade_samples: pixel {} has material {} of {}", i, s.material, materials.size());
    const RenderMaterial& m = materials[s.material];
    if (m.kind == VOXR_MATERIAL_DIELECTRIC) {
      for (int c = 0; c < 3; ++c) out[c] = voxr_shade_dielectric_flat(light.ambient[c], m.absorption[c]);
      continue;
    }
    const glm::vec3 position(s.position[0], s.position[1], s.position[2]);
    const glm::vec3 normal(s.normal[0], s.normal[1], s.normal[2]);
    const LightAtPoint at = light_at(light, position);
    const float cos_theta = glm::dot(normal, at.to_light);
    for (int c = 0; c < 3; ++c)
      out[c] =
          voxr_shade_surface(m.color[c], light.ambient[c], at.irradiance[c], cos_theta, transmittance[i][c]);
  }
  return image;
}

}  // namespace voxr
