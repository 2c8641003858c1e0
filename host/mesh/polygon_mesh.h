// A mesh as a file gives it, before triangulation: world positions in double precision (survey and CAD
// coordinates keep every digit the file has) and polygon faces of any size. Every reader produces one;
// mesh_loader triangulates it and expresses it relative to an anchor (triangle_soup.h).
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "util/surface_look.h"

namespace voxr {

struct PolygonMesh {
  std::vector<glm::dvec3> positions;  // world units, as in the file
  std::vector<uint32_t> indices;      // every face's corners, face after face
  std::vector<uint32_t> face_sizes;   // corners of each face (>= 3 for faces that triangulate)
  std::vector<uint32_t> materials;    // per face; empty when the file has none (material id 0)
  // Surface colour, as the soup's SoupColors gives it (each empty when the file has none):
  std::vector<uint32_t> vertex_rgba;  // per position, RGBA8 (R in the low byte)
  std::vector<glm::vec2> vertex_uv;   // per position, texture coordinates (u right, v up)
  std::vector<uint32_t> face_looks;   // per face, index into looks
  std::vector<SurfaceLook> looks;
  std::vector<SoupTexture> textures;

  size_t face_count() const { return face_sizes.size(); }
  void add_face(const uint32_t* corners, uint32_t count) {
    indices.insert(indices.end(), corners, corners + count);
    face_sizes.push_back(count);
  }
};

}  // namespace voxr
