// Edge topology of a triangle soup: whether it is closed (watertight) and consistently oriented, which
// solid voxelization and refraction need, and the enclosed volume.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/triangle_soup.h"

namespace voxr {

struct MeshTopology {
  size_t boundary = 0;     // undirected edges used by one triangle
  size_t nonmanifold = 0;  // undirected edges used by more than two triangles
  size_t misoriented = 0;  // directed edges used more than once (neighbours disagree on winding)
  bool closed() const { return boundary == 0 && nonmanifold == 0; }
  bool closed_and_oriented() const { return closed() && misoriented == 0; }
};

// Counts over the triangles with material `material`, or all when it is TriangleSoup::kKeepMaterial.
// Edges join triangles that share vertex indices (soups with duplicated vertices count as open).
MeshTopology mesh_topology(const TriangleSoup& soup, uint32_t material = TriangleSoup::kKeepMaterial);

// Sum of signed tetrahedron volumes: the enclosed volume of a closed mesh, positive when normals point out.
double signed_volume(const TriangleSoup& soup);

}  // namespace voxr
