// The shading model of kernels/shading.h evaluated on the host: the Embree reference shades its samples
// with it, and tests shade any method's samples and transmittance with it to compare on equal terms.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

#include "render/environment_map.h"
#include "util/image_rgba.h"
#include "voxr_layout.h"

namespace voxr {

// A width x height image (row-major, top row first, alpha 1) from one SurfaceSample per pixel and the
// transmittance to the light at each (RGB; read only where the sample has a triangle). Per pixel, per
// channel, exactly as kernels/shading.h: no triangle -> ambient; dielectric -> voxr_shade_dielectric_flat;
// opaque and sheet -> voxr_shade_surface(color, ambient, E, n . l, T) with E and l from light_at()
// (render_scene.h) at the sample's position and n its shading normal (already turned to the viewer).
// Throws voxr::Error when the spans are not width * height long or a sample's material id is out of range.
ImageRgba shade_samples(std::span<const SurfaceSample> samples, std::span<const glm::vec3> transmittance,
                        const std::vector<RenderMaterial>& materials, const RenderLight& light,
                        uint32_t width, uint32_t height);

// L at one surface (`s` has a triangle): shade_samples' value for that pixel, given the transmittance from
// `s` to the light. The full refraction reference shades the ends of its branches with it. Throws
// voxr::Error for a material id out of range.
glm::vec3 shade_surface_sample(const SurfaceSample& s, const glm::vec3& transmittance,
                               const std::vector<RenderMaterial>& materials, const RenderLight& light);

// The image of refraction paths (voxr_layout.h RefractionPath), exactly as kernels/shade.cl: per pixel
// fresnel * environment(reflect_direction) + throughput * L(end), where L(end) is environment(exit_direction)
// for an end without a surface and shade_samples' value otherwise. All spans width * height long (throws
// voxr::Error otherwise, or for a material id out of range).
ImageRgba shade_paths(std::span<const SurfaceSample> ends, std::span<const glm::vec3> transmittance,
                      std::span<const RefractionPath> paths, const std::vector<RenderMaterial>& materials,
                      const RenderLight& light, const EnvironmentMap& environment, uint32_t width,
                      uint32_t height);

}  // namespace voxr
