// Merges corners at identical positions (-0 and +0 alike) into one vertex: formats that repeat a vertex per
// face (STL, glTF with per-face attributes) stay closed by index. An open-addressing table of indices into
// the positions, hashed on the double bits: far faster than Assimp's JoinIdenticalVertices or a node-based
// map (2 M-triangle GLB: 2.3 s with Assimp's, about 1 s with std::unordered_map, see the README).
// With `attributes`, a corner is its position and its colour and texture coordinates: corners at one
// position with different colours or UVs (a texture seam) stay apart, and mesh.vertex_rgba and
// mesh.vertex_uv receive each vertex's.
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

#include "mesh/polygon_mesh.h"

namespace voxr {

class CornerWelder {
 public:
  // Appends new positions to mesh.positions; `expected_positions` sizes the table (capped: it may come from
  // a header; the table grows as needed).
  CornerWelder(PolygonMesh& mesh, size_t expected_positions, bool attributes = false)
      : mesh_(mesh), attributes_(attributes) {
    size_t size = 1024;
    while (size < 2 * expected_positions && size < (size_t(1) << 24)) size *= 2;
    slots_.assign(size, kEmpty);
  }

  // The index of `p` in mesh.positions, appended on first sight; `rgba` and `uv` count only with
  // attributes (UVs compared by bits, -0 as +0).
  uint32_t add(const glm::dvec3& p, uint32_t rgba = 0xffffffffu, glm::vec2 uv = glm::vec2(0.0f)) {
    const glm::dvec3 q = p + glm::dvec3(0.0);  // -0 -> +0, so equal positions have equal bits
    uv += glm::vec2(0.0f);
    for (size_t s = hash(q, rgba, uv) & (slots_.size() - 1);; s = (s + 1) & (slots_.size() - 1)) {
      if (slots_[s] == kEmpty) {
        slots_[s] = uint32_t(mesh_.positions.size());
        mesh_.positions.push_back(q);
        if (attributes_) {
          mesh_.vertex_rgba.push_back(rgba);
          mesh_.vertex_uv.push_back(uv);
        }
        if (2 * mesh_.positions.size() > slots_.size()) grow();
        return uint32_t(mesh_.positions.size() - 1);
      }
      const uint32_t id = slots_[s];
      if (mesh_.positions[id] == q &&
          (!attributes_ || (mesh_.vertex_rgba[id] == rgba && mesh_.vertex_uv[id] == uv)))
        return id;
    }
  }

 private:
  static constexpr uint32_t kEmpty = 0xffffffffu;

  size_t hash(const glm::dvec3& p, uint32_t rgba, glm::vec2 uv) const {
    uint64_t bits[3];
    std::memcpy(bits, &p, sizeof bits);
    uint64_t h = bits[0] * 0x9e3779b97f4a7c15ull;
    h = (h ^ (h >> 31) ^ bits[1]) * 0xbf58476d1ce4e5b9ull;
    h = (h ^ (h >> 27) ^ bits[2]) * 0x94d049bb133111ebull;
    if (attributes_) {
      uint64_t a;
      std::memcpy(&a, &uv, sizeof a);
      h = (h ^ (h >> 31) ^ a ^ (uint64_t(rgba) << 17)) * 0x9e3779b97f4a7c15ull;
    }
    return size_t(h ^ (h >> 31));
  }
  size_t hash_of(uint32_t id) const {
    return hash(mesh_.positions[id], attributes_ ? mesh_.vertex_rgba[id] : 0xffffffffu,
                attributes_ ? mesh_.vertex_uv[id] : glm::vec2(0.0f));
  }

  void grow() {
    std::vector<uint32_t> old(2 * slots_.size(), kEmpty);
    old.swap(slots_);
    for (uint32_t id : old)
      if (id != kEmpty)
        for (size_t s = hash_of(id) & (slots_.size() - 1);; s = (s + 1) & (slots_.size() - 1))
          if (slots_[s] == kEmpty) {
            slots_[s] = id;
            break;
          }
  }

  PolygonMesh& mesh_;
  bool attributes_;
  std::vector<uint32_t> slots_;  // indices into mesh_.positions, kEmpty where free
};

}  // namespace voxr
