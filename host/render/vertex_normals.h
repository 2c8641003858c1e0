// Smooth vertex normals for shading (raster_resolve.cl interpolates them across each triangle).
#pragma once

#include <glm/glm.hpp>

#include <vector>

#include "core/triangle_soup.h"

namespace voxr {

// One unit normal per vertex of `soup` (same order as soup.positions): the average of the unit normals
// (b - a) x (c - a) of the triangles that use the vertex, each weighted by the triangle's angle at that
// vertex. Zero-area triangles are ignored; a vertex no valid triangle uses (or whose weighted normals cancel)
// gets (0, 0, 1).
std::vector<glm::vec3> vertex_normals(const TriangleSoup& soup);

}  // namespace voxr
