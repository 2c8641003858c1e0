// The exact reference as the render techniques reach it: the reference techniques (--shadows reference,
// --refraction reference|reference-full) and image-space refraction's d_N precompute ask it for host answers.
// render/ stays free of Embree: reference/embree_reference.h implements it with a ReferenceScene (Embree 3)
// built on first need, so a frame that asks nothing of it builds no BVH.
#pragma once

#include <glm/glm.hpp>

#include <span>
#include <vector>

#include "render/camera_frame.h"
#include "render/environment_map.h"
#include "util/image_rgba.h"
#include "voxr_layout.h"

namespace voxr {

// A host-rendered refraction frame (reference/reference_refraction.h RefractionReference without the BVH
// time): the image shaded on the host, per pixel (row 0 at the top) its path's end, the path, the exact
// transmittance from the end; wall times of the passes in ms, and of the BVH build when this call built it
// (0 otherwise).
struct HostRefraction {
  ImageRgba image;
  std::vector<SurfaceSample> ends;
  std::vector<RefractionPath> paths;
  std::vector<glm::vec3> transmittance;
  double trace_ms = 0.0, shadow_ms = 0.0, shade_ms = 0.0, bvh_build_ms = 0.0;
};

class SceneReference {
 public:
  virtual ~SceneReference() = default;

  // The exact transmittance (straight shadow rays through every surface, RGB) from each sample to `light`;
  // 1 where a sample has no triangle. One per sample, in order.
  virtual std::vector<glm::vec3> transmittance(const RenderLight& light,
                                               std::span<const SurfaceSample> samples) = 0;

  // Wyman 2005 §3's d_N: per vertex of the scene's soup (world units) the distance through its dielectric
  // along -vertex_normals[v]; -1 where unknown (reference/inward_distance.h). Throws voxr::Error when
  // vertex_normals does not have one normal per vertex.
  virtual std::vector<float> inward_distances(const std::vector<glm::vec3>& vertex_normals) = 0;

  // The whole frame traced on the host, one ray per pixel centre: `full` false is the matched model (the
  // refracted path only, the device methods' model), true the full Whitted tree (reflection and refraction
  // at every interface, exact Fresnel). reference/reference_refraction.h has the models.
  virtual HostRefraction refraction(const RenderLight& light, const EnvironmentMap& environment,
                                    const CameraFrame& camera, bool full) = 0;

  // Wall time of the BVH build (0 until something built it), in ms.
  virtual double build_ms() const = 0;
};

}  // namespace voxr
