// Wyman 2005 (Interactive Image-Space Refraction of Nearby Geometry, §3): d_N, per vertex the distance
// through the object along the inverted vertex normal, precomputed offline by ray casting, as the paper does.
#pragma once

#include <glm/glm.hpp>

#include <vector>

#include "core/material.h"
#include "core/triangle_soup.h"
#include "reference/reference_scene.h"

namespace voxr {

// One distance per vertex of `soup` (soup.positions order, world units): from the vertex along
// -vertex_normals[v] to the first surface of the same dielectric (ReferenceScene::intersect_leaving from
// the vertex's first dielectric triangle, so it and the vertex's fan are not hit; surfaces of other
// materials on the way, e.g. an object inside the glass, are passed, and so are surfaces met at the vertex
// itself, within ReferenceScene::kMergeDistance). -1 (unknown: image-space then uses d_V alone) for
// vertices of no dielectric triangle and where the ray finds nothing. A vertex's dielectric is the material
// of the first dielectric triangle (in soup order) that uses it. `materials` are the ones `scene` was built
// with (the ReferenceScene does not expose them): they say which triangles are dielectric. `vertex_normals`
// (render/vertex_normals.h) has one unit normal per vertex. Throws voxr::Error when the sizes or ids do not
// match.
std::vector<float> inward_distances(const ReferenceScene& scene, const TriangleSoup& soup,
                                    const std::vector<Material>& materials,
                                    const std::vector<glm::vec3>& vertex_normals);

}  // namespace voxr
