// The exact refraction reference: Whitted ray tracing with Embree (ReferenceScene::intersect) and the
// material model of kernels/refraction.h, in two forms:
//   matched  follows only the refracted path (total internal reflection mirrors it), 1 - F (Schlick) per
//            refraction, Beer-Lambert inside, Schlick F x one environment mirror lookup at the first surface,
//            up to VOXR_PATH_MAX_EVENTS interfaces: the voxel methods' own model, so their difference from it
//            is their discretisation. Produces the same RefractionPath records the device methods do.
//   full     reflection and refraction both traced at every dielectric interface with the exact Fresnel
//            reflectance (voxr_fresnel_exact) until a branch's weight (its largest channel of the
//            throughput to the pixel) falls below 1e-3, with `max_interfaces` per branch only as a guard
//            against loops; reflected rays that reach an opaque surface are shaded there like any other: the
//            difference from it is the model's.
// Opaque ends are shaded by the one shading model with the exact shadow transmittance
// (ReferenceScene::transmittance) from the end point (shade_host.h shade_surface_sample).
// Both: the camera ray's first surface, if opaque or a sheet, is shaded there (the primary sample, as every
// method); any later ray crosses sheets, times their transmittance. A ray leaving a surface skips the
// triangle it left (and coincident ones passed at the same point), nothing else
// (ReferenceScene::intersect_leaving); of coincident surfaces met together an opaque one wins, then the
// lowest triangle id (ReferenceScene::intersect), so glass standing on a floor ends its rays on the floor.
// Nested media are tracked as every refraction kernel tracks them (kernels/common/media_stack.h: entered or
// left by the hit triangle's winding, ReferenceScene::winding_normal; an entry per material with a count).
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "reference/reference_scene.h"
#include "render/camera_frame.h"
#include "render/environment_map.h"
#include "util/image_rgba.h"
#include "voxr_layout.h"

namespace voxr {

enum class ReferenceModel { kMatched, kFull };

struct RefractionReference {
  ImageRgba image;                       // camera.width x camera.height, linear RGB, alpha 1
  std::vector<SurfaceSample> ends;       // per pixel: where its (refracted) path ends; VOXR_NO_TRIANGLE: the
                                         // environment, in paths[i].exit_direction
  std::vector<RefractionPath> paths;     // per pixel: the matched model's path (the full model's too: its
                                         // transmitted branch), as the device methods write them
  std::vector<glm::vec3> transmittance;  // per pixel: to the light from its end (1 where it has no surface)
  double build_ms = 0.0;                 // the BVH build (ReferenceScene::build_ms)
  // Wall time of each pass (all cores): trace the matched paths (and, full model, the whole full image,
  // its shadow rays and shading included: its shade_ms is 0), the shadow rays from `ends`, shade_paths.
  double trace_ms = 0.0, shadow_ms = 0.0, shade_ms = 0.0;
};

// Renders `scene` as `camera` sees it, one ray per pixel centre (camera.ray_direction(x + 0.5, y + 0.5)).
// `materials` are render_materials() of the scene's (ids as in the ReferenceScene). Primary ray misses
// show environment.lookup(direction). max_interfaces: the full model's guard (dielectric interfaces per
// branch, then the branch is dropped); the matched model stops at VOXR_PATH_MAX_EVENTS. Throws voxr::Error
// for an empty camera or a material id out of range.
RefractionReference render_refraction_reference(const ReferenceScene& scene,
                                                const std::vector<RenderMaterial>& materials,
                                                const RenderLight& light, const EnvironmentMap& environment,
                                                const CameraFrame& camera, ReferenceModel model,
                                                uint32_t max_interfaces = 64);

}  // namespace voxr
