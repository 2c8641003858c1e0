// The scene as the kernels read it: vertex positions (float4, w = 1) and triangles (uint4: three vertex
// indices and the material id in w). Loaders and generators all produce this; nothing else is uploaded.
// Positions are relative to `anchor` (world = anchor + position, in double): a mesh far from the origin
// (survey or CAD coordinates) keeps float precision relative to its own size, as one at the origin does.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "util/host_array.h"
#include "util/surface_look.h"

namespace voxr {

struct Bounds {
  glm::vec3 lo{std::numeric_limits<float>::max()};
  glm::vec3 hi{-std::numeric_limits<float>::max()};

  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  void extend(const glm::vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void extend(const Bounds& b) {
    if (!b.empty()) {
      extend(b.lo);
      extend(b.hi);
    }
  }
  glm::vec3 size() const { return empty() ? glm::vec3(0) : hi - lo; }
};

// The surface colour a mesh carries, parallel to the soup's arrays; every array may be empty: no vertex
// colours means white, no UVs means the texture is not sampled (the factor alone), no triangle_look means
// look 0 for every triangle, no looks means white. Colour is an input of the `color` channel only; the
// other channels and the renderer ignore it.
struct SoupColors {
  HostArray<uint32_t> vertex_rgba;    // per vertex, RGBA8 (R in the low byte)
  HostArray<glm::vec2> vertex_uv;     // per vertex texture coordinates (u right, v up)
  HostArray<uint32_t> triangle_look;  // per triangle, index into looks
  std::vector<SurfaceLook> looks;
  std::vector<SoupTexture> textures;
  bool empty() const { return vertex_rgba.empty() && looks.empty(); }
};

struct TriangleSoup {
  glm::dvec3 anchor{0.0};  // world position of the frame the positions are in
  // Page-aligned, so a CPU device reads them in place (host_array.h).
  HostArray<glm::vec4> positions;   // relative to anchor; w = 1
  HostArray<glm::uvec4> triangles;  // xyz: indices into positions, w: material id
  SoupColors colors;                // surface colour, when the mesh has any (empty otherwise)

  size_t triangle_count() const { return triangles.size(); }
  size_t vertex_count() const { return positions.size(); }
  bool empty() const { return triangles.empty(); }

  // Bounds of the vertices that triangles use, relative to anchor.
  Bounds bounds() const;
  // Appends `other` with every world position transformed by `transform` (in double, then expressed
  // relative to this soup's anchor); its material ids are replaced by `material` unless it is kKeepMaterial.
  static constexpr uint32_t kKeepMaterial = 0xffffffffu;
  void append(const TriangleSoup& other, const glm::mat4& transform = glm::mat4(1.0f),
              uint32_t material = kKeepMaterial);
};

// The anchor for world positions within [lo, hi]: lo rounded down to a multiple of the power of two at or
// above the box's size, so positions relative to it lie in [0, 2 size) (float keeps 2^-23 of the size), and
// translating a mesh by a multiple of that power of two moves the anchor by exactly the translation and
// leaves the float positions bit for bit the same.
glm::dvec3 choose_anchor(const glm::dvec3& lo, const glm::dvec3& hi);

// Throws voxr::Error naming `source` when the soup is empty, an index is out of range or a vertex that a
// triangle uses is NaN or infinite. Returns the number of degenerate (zero-area) triangles, which are kept:
// conservative voxelization treats them as the segment or point they are.
size_t validate_soup(const TriangleSoup& soup, const std::string& source);

}  // namespace voxr
