// Smooth vertex normals of an indexed triangle mesh, the one definition the rasterizer's resolve and the
// Embree reference interpolate for the shading normal.
#pragma once

#include <glm/glm.hpp>

#include <vector>

#include "core/triangle_soup.h"

namespace voxr {

// One unit normal per vertex of `soup` (same indexing as soup.positions): the sum over the triangles using
// the vertex of each triangle's unit normal (right-handed from its winding, cross(p1 - p0, p2 - p0))
// weighted by the triangle's angle at that vertex (Thurmer and Wuthrich 1998), normalized. Zero-area
// triangles are ignored; a vertex that no triangle of non-zero area uses, or whose weighted normals cancel,
// gets (0, 0, 1). Computed in double. Throws voxr::Error for a vertex index out of range.
std::vector<glm::vec3> vertex_normals(const TriangleSoup& soup);

}  // namespace voxr
