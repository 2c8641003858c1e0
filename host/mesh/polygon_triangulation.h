// Polygon faces -> triangles. Convex polygons are fanned from their first corner (that is exact for them);
// every other polygon is projected onto its best-fit plane (Newell's normal) and triangulated by CGAL's
// constrained Delaunay triangulation, keeping the triangles inside the boundary, so a concave face covers
// exactly its own area. Polygons that are not planar or cross themselves have no single right answer: they
// are counted for a warning, and self-crossing ones are fanned.
#pragma once

#include <glm/glm.hpp>

#include <cstddef>
#include <string>
#include <vector>

#include "mesh/polygon_mesh.h"
#include "util/host_array.h"

namespace voxr {

struct TriangulationReport {
  size_t polygons = 0;           // faces of 4 or more corners
  size_t concave = 0;            // of them, triangulated by constrained Delaunay triangulation
  size_t nonplanar = 0;          // corners further than 0.1 % of the face's size from its plane
  size_t self_intersecting = 0;  // boundary crosses itself or repeats a corner position: fanned
  size_t too_small = 0;          // faces of fewer than 3 corners (no area; dropped)
  size_t first_nonplanar = SIZE_MAX, first_self_intersecting = SIZE_MAX;  // face indices, for messages

  // One line per kind found, each naming `source` and the first face at fault; empty when all is well.
  std::vector<std::string> warnings(const std::string& source) const;
};

// Appends the triangles of every face of `mesh` to `out`: xyz index mesh.positions, w is the face's
// material (mesh.materials, or 0). Triangles keep the face's winding. When `looks` is given and the mesh
// has face_looks, each triangle's face look is appended to it (parallel to the triangles appended to `out`).
void triangulate(const PolygonMesh& mesh, HostArray<glm::uvec4>& out, TriangulationReport& report,
                 HostArray<uint32_t>* looks = nullptr);

}  // namespace voxr
