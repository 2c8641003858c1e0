#include "render/shade_host.h"

#include "render/render_scene.h"
#include "shading.h"
#include "util/error.h"

namespace voxr {

namespace {

// L at a sample with a surface (kernels/shade.cl's surface branch).
glm::vec3 shade_surface(const SurfaceSample& s, const glm::vec3& transmittance,
                        const std::vector<RenderMaterial>& materials, const RenderLight& light,
                        size_t pixel) {
  if (s.material >= materials.size())
    fail("shade: pixel {} has material {} of {}", pixel, s.material, materials.size());
  const RenderMaterial& m = materials[s.material];
  glm::vec3 out;
  if (m.kind == VOXR_MATERIAL_DIELECTRIC) {
    for (int c = 0; c < 3; ++c) out[c] = voxr_shade_dielectric_flat(light.ambient[c], m.absorption[c]);
    return out;
  }
  const glm::vec3 position(s.position[0], s.position[1], s.position[2]);
  const glm::vec3 normal(s.normal[0], s.normal[1], s.normal[2]);
  const LightAtPoint at = light_at(light, position);
  const float cos_theta = glm::dot(normal, at.to_light);
  for (int c = 0; c < 3; ++c)
    out[c] = voxr_shade_surface(m.color[c], light.ambient[c], at.irradiance[c], cos_theta, transmittance[c]);
  return out;
}

void check_sizes(size_t samples, size_t transmittance, size_t pixels, uint32_t width, uint32_t height) {
  if (samples != pixels || transmittance != pixels)
    fail("shade: {} samples and {} transmittances for a {}x{} image", samples, transmittance, width, height);
}

glm::vec3 vec(const float* v) {
  return glm::vec3(v[0], v[1], v[2]);
}

}  // namespace

glm::vec3 shade_surface_sample(const SurfaceSample& s, const glm::vec3& transmittance,
                               const std::vector<RenderMaterial>& materials, const RenderLight& light) {
  if (s.material >= materials.size())
    fail("shade: a sample has material {} of {}", s.material, materials.size());
  return shade_surface(s, transmittance, materials, light, 0);
}

ImageRgba shade_samples(std::span<const SurfaceSample> samples, std::span<const glm::vec3> transmittance,
                        const std::vector<RenderMaterial>& materials, const RenderLight& light,
                        uint32_t width, uint32_t height) {
  const size_t pixels = size_t(width) * height;
  check_sizes(samples.size(), transmittance.size(), pixels, width, height);
  ImageRgba image(width, height, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  for (size_t i = 0; i < pixels; ++i) {
    const glm::vec3 c = samples[i].triangle == VOXR_NO_TRIANGLE
                            ? vec(light.ambient)
                            : shade_surface(samples[i], transmittance[i], materials, light, i);
    image.pixels[i] = glm::vec4(c, 1.0f);
  }
  return image;
}

ImageRgba shade_paths(std::span<const SurfaceSample> ends, std::span<const glm::vec3> transmittance,
                      std::span<const RefractionPath> paths, const std::vector<RenderMaterial>& materials,
                      const RenderLight& light, const EnvironmentMap& environment, uint32_t width,
                      uint32_t height) {
  const size_t pixels = size_t(width) * height;
  check_sizes(ends.size(), transmittance.size(), pixels, width, height);
  if (paths.size() != pixels) fail("shade: {} paths for a {}x{} image", paths.size(), width, height);
  ImageRgba image(width, height, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  for (size_t i = 0; i < pixels; ++i) {
    const RefractionPath& p = paths[i];
    glm::vec3 c(0.0f);
    if (!(p.events & VOXR_PATH_LOST)) {
      const glm::vec3 end = ends[i].triangle == VOXR_NO_TRIANGLE
                                ? environment.lookup(vec(p.exit_direction))
                                : shade_surface(ends[i], transmittance[i], materials, light, i);
      c = vec(p.throughput) * end;
    }
    if (p.fresnel > 0.0f) c += p.fresnel * environment.lookup(vec(p.reflect_direction));
    image.pixels[i] = glm::vec4(c, 1.0f);
  }
  return image;
}

}  // namespace voxr
