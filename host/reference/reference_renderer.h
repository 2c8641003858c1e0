// The reference image: one primary ray per pixel through the Embree scene, the exact shadow transmittance at
// every hit, shaded on the host by the one shading model (kernels/shading.h through render/shade_host.h).
#pragma once

#include <glm/glm.hpp>

#include <span>
#include <vector>

#include "reference/reference_scene.h"
#include "render/camera_frame.h"
#include "util/image_rgba.h"
#include "voxr_layout.h"

namespace voxr {

struct ReferenceRender {
  ImageRgba image;                       // camera.width x camera.height, linear RGB, alpha 1
  std::vector<SurfaceSample> samples;    // per pixel (y * width + x): what its primary ray hit
  std::vector<glm::vec3> transmittance;  // per pixel: to the light from the hit (1 where nothing was hit)
  double build_ms = 0.0;                 // the scene's BVH build (ReferenceScene::build_ms)
  double primary_ms = 0.0, shadow_ms = 0.0, shade_ms = 0.0;  // wall time of each pass
};

// Renders `scene` as `camera` sees it: the ray from camera.eye along camera.ray_direction(x + 0.5, y + 0.5)
// for pixel (x, y), ReferenceScene::intersect from t = 0 (the eye), ReferenceScene::transmittance at each
// hit, shade_samples() with `materials` (render_materials() of the scene's materials: ids must match the
// ones the ReferenceScene was built with). Primary and shadow passes run on all cores. Throws voxr::Error
// for an empty camera or a material id out of range.
ReferenceRender render_reference(const ReferenceScene& scene, const std::vector<RenderMaterial>& materials,
                                 const RenderLight& light, const CameraFrame& camera);

// The exact transmittance at each sample (1 where it has no triangle): the reference answer a shadow method
// is measured against. ReferenceScene::transmittance over the samples, on all cores.
std::vector<glm::vec3> reference_transmittance(const ReferenceScene& scene, const RenderLight& light,
                                               std::span<const SurfaceSample> samples);

}  // namespace voxr
