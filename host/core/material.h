// Surface materials, one model shared by the voxel methods and the reference renderer (DESIGN.md,
// "Materials and the reference"). A triangle's material id is an index into Scene::materials.
#pragma once

#include <glm/glm.hpp>

#include <string>

namespace voxr {

enum class MaterialKind {
  kOpaque,      // diffuse surface of colour `color`
  kDielectric,  // refracting solid of index `ior`; Beer-Lambert absorption `absorption` inside; mesh closed
  kSheet,       // thin surface (leaf, paper): light passing through is scaled by `transmittance` per crossing
};

struct Material {
  std::string name;
  MaterialKind kind = MaterialKind::kOpaque;
  glm::vec3 color{0.8f};          // diffuse reflectance (opaque, sheet), each channel in [0, 1]
  float ior = 1.5f;               // index of refraction (dielectric), > 0
  glm::vec3 absorption{0.0f};     // sigma_a per world unit, RGB (dielectric), >= 0
  glm::vec3 transmittance{1.0f};  // per crossing, RGB in [0, 1] (sheet)
};

// "opaque", "dielectric", "sheet": the names the scene format uses.
inline const char* material_kind_name(MaterialKind kind) {
  switch (kind) {
    case MaterialKind::kOpaque:
      return "opaque";
    case MaterialKind::kDielectric:
      return "dielectric";
    case MaterialKind::kSheet:
      return "sheet";
  }
  return "?";
}

}  // namespace voxr
