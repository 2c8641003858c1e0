#include "reference/inward_distance.h"

#include <cmath>
#include <cstdint>

#include "reference/parallel_blocks.h"
#include "util/error.h"

namespace voxr {

namespace {

// The ray from a vertex ignores hits nearer than this, relative to ReferenceScene::scene_size(): the
// vertex's own triangles, which it lies on.
constexpr float kVertexEpsilon = 1e-4f;
// Surfaces of other materials passed at most before giving up (0 then).
constexpr int kMaxSkipped = 64;
constexpr uint32_t kNoMaterial = 0xffffffffu;

}  // namespace

std::vector<float> inward_distances(const ReferenceScene& scene, const TriangleSoup& soup,
                                    const std::vector<Material>& materials,
                                    const std::vector<glm::vec3>& vertex_normals) {
  const size_t n = soup.positions.size();
  if (vertex_normals.size() != n)
    fail("inward distances: {} vertex normals for {} vertices", vertex_normals.size(), n);
  // Each vertex's dielectric: the material of the first dielectric triangle that uses it.
  std::vector<uint32_t> owner(n, kNoMaterial);
  for (size_t i = 0; i < soup.triangles.size(); ++i) {
    const glm::uvec4& t = soup.triangles[i];
    if (t.w >= materials.size())
      fail("inward distances: triangle {} has material {} but there are {} materials", i, t.w,
           materials.size());
    if (materials[t.w].kind != MaterialKind::kDielectric) continue;
    for (int c = 0; c < 3; ++c) {
      if (t[c] >= n) fail("inward distances: triangle {} names vertex {} but there are {}", i, t[c], n);
      if (owner[t[c]] == kNoMaterial) owner[t[c]] = t.w;
    }
  }

  const float epsilon = kVertexEpsilon * scene.scene_size();
  std::vector<float> out(n, -1.0f);  // unknown: image-space falls back to d_V
  parallel_blocks(n, 1024, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v) {
      if (owner[v] == kNoMaterial) continue;
      const glm::vec3 dir = -vertex_normals[v];
      const float len = glm::length(dir);
      if (!(len > 0.0f) || !std::isfinite(len)) continue;
      const glm::vec3 origin(soup.positions[v]);
      float t_near = epsilon;
      for (int skipped = 0; skipped <= kMaxSkipped; ++skipped) {
        const SurfaceSample hit = scene.intersect(origin, dir / len, t_near);
        if (hit.triangle == VOXR_NO_TRIANGLE) break;
        if (hit.material == owner[v]) {
          out[v] = hit.distance;
          break;
        }
        t_near = hit.distance + epsilon;  // another material's surface (nested inside): pass it
      }
    }
  });
  return out;
}

}  // namespace voxr
