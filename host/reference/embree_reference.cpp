#include "reference/embree_reference.h"

#include "reference/inward_distance.h"
#include "reference/reference_refraction.h"
#include "reference/reference_renderer.h"
#include "render/render_scene.h"

namespace voxr {

EmbreeReference::EmbreeReference(const TriangleSoup& soup, const std::vector<Material>& materials)
    : soup_(soup), materials_(materials) {}

EmbreeReference::EmbreeReference(const ReferenceScene& scene, const TriangleSoup& soup,
                                 const std::vector<Material>& materials)
    : soup_(soup), materials_(materials), scene_(&scene) {}

EmbreeReference::~EmbreeReference() = default;

const ReferenceScene& EmbreeReference::scene() {
  if (scene_ == nullptr) {
    owned_ = std::make_unique<ReferenceScene>(soup_, materials_);
    scene_ = owned_.get();
  }
  return *scene_;
}

std::vector<glm::vec3> EmbreeReference::transmittance(const RenderLight& light,
                                                      std::span<const SurfaceSample> samples) {
  return reference_transmittance(scene(), light, samples);
}

std::vector<float> EmbreeReference::inward_distances(const std::vector<glm::vec3>& vertex_normals) {
  return voxr::inward_distances(scene(), soup_, materials_, vertex_normals);
}

HostRefraction EmbreeReference::refraction(const RenderLight& light, const EnvironmentMap& environment,
                                           const CameraFrame& camera, bool full) {
  const bool built_here = scene_ == nullptr;
  RefractionReference r =
      render_refraction_reference(scene(), render_materials(materials_), light, environment, camera,
                                  full ? ReferenceModel::kFull : ReferenceModel::kMatched);
  HostRefraction out{std::move(r.image), std::move(r.ends), std::move(r.paths), std::move(r.transmittance)};
  out.trace_ms = r.trace_ms;
  out.shadow_ms = r.shadow_ms;
  out.shade_ms = r.shade_ms;
  out.bvh_build_ms = built_here ? scene_->build_ms() : 0.0;
  return out;
}

double EmbreeReference::build_ms() const {
  return scene_ ? scene_->build_ms() : 0.0;
}

}  // namespace voxr
