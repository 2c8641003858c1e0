// Midpoint subdivision: the cheap way to raise a scene's triangle count without changing its shape, for
// scaling benchmarks (the papers time the same model at several triangle counts).
#pragma once

#include "core/triangle_soup.h"

namespace voxr {

// Each level splits every triangle into four at its edge midpoints: 4^levels times the triangles. Each
// undirected edge (pair of vertex indices) gets one midpoint vertex, so closed meshes stay closed; the
// corner triangles keep their parent's winding and material id. Positions stay on the original flat
// triangles, so volume and bounds do not change. Throws voxr::Error for levels < 0 or a result beyond
// 2^31 triangles or vertices.
TriangleSoup subdivide_midpoint(const TriangleSoup& soup, int levels);

}  // namespace voxr
