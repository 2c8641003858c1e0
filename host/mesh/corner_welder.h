// Merges corners at identical positions (-0 and +0 alike) into one vertex: formats that repeat a vertex per
// face (STL, glTF with per-face attributes) stay closed by index. An open-addressing table of indices into
// the positions, hashed on the double bits: far faster than Assimp's JoinIdenticalVertices or a node-based
// map (2 M-triangle GLB: 2.3 s with Assimp's, about 1 s with std::unordered_map, see the README).
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
  CornerWelder(PolygonMesh& mesh, size_t expected_positions) : mesh_(mesh) {
    size_t size = 1024;
    while (size < 2 * expected_positions && size < (size_t(1) << 24)) size *= 2;
    slots_.assign(size, kEmpty);
  }

  // The index of `p` in mesh.positions, appended on first sight.
  uint32_t add(const glm::dvec3& p) {
    const glm::dvec3 q = p + glm::dvec3(0.0);  // -0 -> +0, so equal positions have equal bits
    for (size_t s = hash(q) & (slots_.size() - 1);; s = (s + 1) & (slots_.size() - 1)) {
      if (slots_[s] == kEmpty) {
        slots_[s] = uint32_t(mesh_.positions.size());
        mesh_.positions.push_back(q);
        if (2 * mesh_.positions.size() > slots_.size()) grow();
        return uint32_t(mesh_.positions.size() - 1);
      }
      if (mesh_.positions[slots_[s]] == q) return slots_[s];
    }
  }

 private:
  static constexpr uint32_t kEmpty = 0xffffffffu;

  static size_t hash(const glm::dvec3& p) {
    uint64_t bits[3];
    std::memcpy(bits, &p, sizeof bits);
    uint64_t h = bits[0] * 0x9e3779b97f4a7c15ull;
    h = (h ^ (h >> 31) ^ bits[1]) * 0xbf58476d1ce4e5b9ull;
    h = (h ^ (h >> 27) ^ bits[2]) * 0x94d049bb133111ebull;
    return size_t(h ^ (h >> 31));
  }

  void grow() {
    std::vector<uint32_t> old(2 * slots_.size(), kEmpty);
    old.swap(slots_);
    for (uint32_t id : old)
      if (id != kEmpty)
        for (size_t s = hash(mesh_.positions[id]) & (slots_.size() - 1);; s = (s + 1) & (slots_.size() - 1))
          if (slots_[s] == kEmpty) {
            slots_[s] = id;
            break;
          }
  }

  PolygonMesh& mesh_;
  std::vector<uint32_t> slots_;  // indices into mesh_.positions, kEmpty where free
};

}  // namespace voxr
