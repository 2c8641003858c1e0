#include "reference/inward_distance.h"

#include <cmath>
#include <cstdint>
#include <span>

#include "reference/parallel_blocks.h"
#include "util/error.h"

namespace voxr {

namespace {

// Surfaces passed at most before giving up (-1 then): of other materials, or of the same one at the vertex
// itself.
constexpr int kMaxSkipped = 64;
constexpr uint32_t kNoMaterial = 0xffffffffu;

}  // namespace

std::vector<float> inward_distances(const ReferenceScene& scene, const TriangleSoup& soup,
                                    const std::vector<Material>& materials,
                                    const std::vector<glm::vec3>& vertex_normals) {
  const size_t n = soup.positions.size();
  if (vertex_normals.size() != n)
    fail("inward distances: {} vertex normals for {} vertices", vertex_normals.size(), n);
  // Each vertex's dielectric: the material of the first dielectric triangle that uses it (owner_triangle).
  std::vector<uint32_t> owner(n, kNoMaterial), owner_triangle(n, 0);
  for (size_t i = 0; i < soup.triangles.size(); ++i) {
    const glm::uvec4& t = soup.triangles[i];
    if (t.w >= materials.size())
      fail("inward distances: triangle {} has material {} but there are {} materials", i, t.w,
           materials.size());
    if (materials[t.w].kind != MaterialKind::kDielectric) continue;
    for (int c = 0; c < 3; ++c) {
      if (t[c] >= n) fail("inward distances: triangle {} names vertex {} but there are {}", i, t[c], n);
      if (owner[t[c]] == kNoMaterial) {
        owner[t[c]] = t.w;
        owner_triangle[t[c]] = uint32_t(i);
      }
    }
  }

  const float merge = ReferenceScene::kMergeDistance * scene.scene_size();
  std::vector<float> out(n, -1.0f);  // unknown: image-space falls back to d_V
  parallel_blocks(n, 1024, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v) {
      if (owner[v] == kNoMaterial) continue;
      const glm::vec3 dir = -vertex_normals[v];
      const float len = glm::length(dir);
      if (!(len > 0.0f) || !std::isfinite(len)) continue;
      // The ray leaves the vertex's triangle (and so its fan, which shares the vertex); a surface met at
      // the vertex itself (a split vertex's fan, a coincident face) is passed as one of another material.
      glm::vec3 origin(soup.positions[v]);
      uint32_t left[8] = {owner_triangle[v]};
      uint32_t left_count = 1;
      float travelled = 0.0f;
      for (int skipped = 0; skipped <= kMaxSkipped; ++skipped) {
        const SurfaceSample hit = scene.intersect_leaving(origin, dir / len, std::span(left, left_count));
        if (hit.triangle == VOXR_NO_TRIANGLE) break;
        travelled += hit.distance;
        if (hit.material == owner[v] && travelled > merge) {
          out[v] = travelled;
          break;
        }
        origin = glm::vec3(hit.position[0], hit.position[1], hit.position[2]);
        if (hit.distance <= merge && left_count < 8) {
          left[left_count++] = hit.triangle;
        } else {
          left[0] = hit.triangle;
          left_count = 1;
        }
      }
    }
  });
  return out;
}

}  // namespace voxr
