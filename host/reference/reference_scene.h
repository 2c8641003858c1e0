// The exact reference for everything that renders (DESIGN.md, "Materials and the reference"): the scene's
// triangles in an Embree 3 BVH, intersected in single precision with Embree's watertight test, positions
// relative to the scene's anchor as everywhere else.
//
// Shadow rays are straight (not refracted): their transmittance is the product of every sheet's per-crossing
// transmittance and exp(-sigma_a * length) through every dielectric along the segment to the light; an
// opaque hit blocks. That is the quantity a transparent shadow map approximates.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/material.h"
#include "core/triangle_soup.h"
#include "voxr_layout.h"

namespace voxr {

class ReferenceScene {
 public:
  // Builds the BVH over `soup` (material ids index `materials`). Throws voxr::Error when Embree fails or a
  // material id is out of range. The soup is copied.
  ReferenceScene(const TriangleSoup& soup, const std::vector<Material>& materials);
  ~ReferenceScene();
  ReferenceScene(const ReferenceScene&) = delete;
  ReferenceScene& operator=(const ReferenceScene&) = delete;

  double build_ms() const;  // wall time of the BVH build

  // The nearest hit of the ray origin + t * dir, t in (t_near, t_far), as a SurfaceSample (triangle =
  // VOXR_NO_TRIANGLE on a miss; normals unit and turned towards the origin; shading normal interpolated from
  // angle-weighted vertex normals, as the rasterizer's resolve does).
  SurfaceSample intersect(const glm::vec3& origin, const glm::vec3& dir, float t_near = 0.0f,
                          float t_far = 3.0e38f) const;

  // RGB transmittance from `point` (on triangle `self`, VOXR_NO_TRIANGLE for none) to the light, along the
  // straight segment. Every crossing counts once: a ray through an edge shared by two triangles of one mesh
  // crosses one surface, two coincident triangles are two surfaces.
  glm::vec3 transmittance(const RenderLight& light, const glm::vec3& point, uint32_t self) const;
  // The same for every sample with a triangle (others get 1), on all cores.
  std::vector<glm::vec3> transmittance(const RenderLight& light,
                                       std::span<const SurfaceSample> samples) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace voxr
