// The render techniques' exact reference (render/scene_reference.h) with Embree: a ReferenceScene (BVH) of
// the scene's soup, built on the first question (or borrowed from the caller), answering with
// reference_transmittance, inward_distances and render_refraction_reference.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "core/material.h"
#include "core/triangle_soup.h"
#include "reference/reference_scene.h"
#include "render/scene_reference.h"

namespace voxr {

class EmbreeReference final : public SceneReference {
 public:
  // The reference of `soup` with `materials` (both must outlive it): the BVH is built on first need.
  EmbreeReference(const TriangleSoup& soup, const std::vector<Material>& materials);
  // The same over a BVH the caller already has (built from the same soup and materials; must outlive it).
  EmbreeReference(const ReferenceScene& scene, const TriangleSoup& soup,
                  const std::vector<Material>& materials);
  ~EmbreeReference() override;

  // The BVH, built now if it was not.
  const ReferenceScene& scene();

  std::vector<glm::vec3> transmittance(const RenderLight& light,
                                       std::span<const SurfaceSample> samples) override;
  std::vector<float> inward_distances(const std::vector<glm::vec3>& vertex_normals) override;
  HostRefraction refraction(const RenderLight& light, const EnvironmentMap& environment,
                            const CameraFrame& camera, bool full) override;
  double build_ms() const override;

 private:
  const TriangleSoup& soup_;
  const std::vector<Material>& materials_;
  std::unique_ptr<ReferenceScene> owned_;
  const ReferenceScene* scene_ = nullptr;
};

}  // namespace voxr
