#include "reference/reference_renderer.h"

#include "reference/parallel_blocks.h"
#include "render/shade_host.h"
#include "util/clock.h"
#include "util/error.h"

namespace voxr {

ReferenceRender render_reference(const ReferenceScene& scene, const std::vector<RenderMaterial>& materials,
                                 const RenderLight& light, const CameraFrame& camera) {
  if (camera.width == 0 || camera.height == 0)
    fail("reference render: the camera has {}x{} pixels", camera.width, camera.height);
  ReferenceRender out;
  out.build_ms = scene.build_ms();
  const uint32_t width = camera.width;
  out.samples.resize(size_t(width) * camera.height);

  Clock::time_point start = Clock::now();
  // One row per block: neighbouring rays share BVH nodes.
  parallel_blocks(camera.height, 1, [&](size_t y0, size_t y1) {
    for (size_t y = y0; y < y1; ++y)
      for (uint32_t x = 0; x < width; ++x)
        out.samples[y * width + x] =
            scene.intersect(camera.eye, camera.ray_direction(float(x) + 0.5f, float(y) + 0.5f));
  });
  out.primary_ms = ms_since(start);

  start = Clock::now();
  out.transmittance = reference_transmittance(scene, light, out.samples);
  out.shadow_ms = ms_since(start);

  start = Clock::now();
  out.image = shade_samples(out.samples, out.transmittance, materials, light, width, camera.height);
  out.shade_ms = ms_since(start);
  return out;
}

std::vector<glm::vec3> reference_transmittance(const ReferenceScene& scene, const RenderLight& light,
                                               std::span<const SurfaceSample> samples) {
  return scene.transmittance(light, samples);
}

}  // namespace voxr
