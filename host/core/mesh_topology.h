// Edge topology of a triangle soup: whether it is closed (watertight) and consistently oriented, which
// solid voxelization and refraction need, and the enclosed volume.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "core/triangle_soup.h"

namespace voxr {

struct MeshTopology {
  size_t boundary = 0;        // undirected edges used by one triangle
  size_t nonmanifold = 0;     // undirected edges used by more than two triangles
  size_t misoriented = 0;     // directed edges used more than once (neighbours disagree on winding)
  size_t duplicates = 0;      // triangles repeating an earlier one's corners in the same orientation
  size_t opposite_pairs = 0;  // pairs of triangles on the same corners in opposite orientations
  // Midpoints of the first boundary and non-manifold edge found (soup frame), for messages.
  glm::vec3 boundary_at{0.0f}, nonmanifold_at{0.0f};
  size_t first_duplicate = 0;  // soup index of the first copy (when duplicates > 0)
  bool closed() const { return boundary == 0 && nonmanifold == 0; }
  bool closed_and_oriented() const { return closed() && misoriented == 0; }
  // "3 boundary edges (first at (x, y, z)), 1 triangle listed twice, ...": what was found, for warnings.
  std::string describe(const glm::dvec3& anchor) const;
};

// Counts over the triangles with material `material`, or all when it is TriangleSoup::kKeepMaterial.
// Edges join triangles whose corners are at the same positions, whether or not they share vertex indices
// (an STL-like soup that repeats vertices is as closed as its geometry). Duplicates are judged as the
// generalized winding number (inside where it is >= 1/2) judges them: a same-orientation copy changes no
// inside, so it is counted in `duplicates` and left out of the edge counts; an opposite-orientation pair
// cancels, so both are counted in `opposite_pairs` and left out. Welding and the duplicate search run only
// when the edges by index are not closed (the common closed case costs one counting sort); a closed mesh
// keeps duplicates that cancel in pairs, which parity handles as it should.
MeshTopology mesh_topology(const TriangleSoup& soup, uint32_t material = TriangleSoup::kKeepMaterial);

// Removes triangles that repeat an earlier triangle's corner positions in the same orientation (cyclic
// order); returns how many. Parity solid fill counts every crossing, so copies must go before it.
size_t drop_duplicate_triangles(TriangleSoup& soup);

// Sum of signed tetrahedron volumes: the enclosed volume of a closed mesh, positive when normals point out.
double signed_volume(const TriangleSoup& soup);

}  // namespace voxr
