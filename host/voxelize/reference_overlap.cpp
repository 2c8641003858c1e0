#include "voxelize/reference_overlap.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <thread>
#include <vector>

namespace voxr {

glm::dvec3 grid_coords_exact(const GridSpec& grid, const glm::vec4& p) {
  const glm::dvec3 d = glm::dvec3(glm::vec3(p)) - glm::dvec3(grid.origin);
  const double h = grid.voxel_size;
  return {glm::dot(glm::dvec3(grid.axes[0]), d) / h, glm::dot(glm::dvec3(grid.axes[1]), d) / h,
          glm::dot(glm::dvec3(grid.axes[2]), d) / h};
}

bool overlap_exact(const glm::dvec3 (&v)[3], int64_t i, int64_t j, int64_t k, double widen) {
  const glm::dvec3 c(double(i) + 0.5, double(j) + 0.5, double(k) + 0.5);
  const glm::dvec3 p[3] = {v[0] - c, v[1] - c, v[2] - c};
  auto separated = [&](const glm::dvec3& axis) {
    const double a = glm::dot(axis, p[0]), b = glm::dot(axis, p[1]), d = glm::dot(axis, p[2]);
    const double r = (0.5 + widen) * (std::abs(axis.x) + std::abs(axis.y) + std::abs(axis.z));
    return std::min({a, b, d}) > r || std::max({a, b, d}) < -r;
  };
  for (int a = 0; a < 3; ++a) {
    glm::dvec3 axis(0.0);
    axis[a] = 1.0;
    if (separated(axis)) return false;
  }
  if (separated(glm::cross(p[1] - p[0], p[2] - p[0]))) return false;
  for (int e = 0; e < 3; ++e) {
    const glm::dvec3 d = p[(e + 1) % 3] - p[e];
    if (separated({0.0, d.z, -d.y}) || separated({-d.z, 0.0, d.x}) || separated({d.y, -d.x, 0.0}))
      return false;
  }
  return true;
}

VoxelGrid reference_overlap(const TriangleSoup& soup, const GridSpec& grid, double widen) {
  VoxelGrid out;
  out.spec = grid;
  out.occ.assign((grid.voxel_count() + 31) / 32, 0u);
  const size_t n = soup.triangle_count();
  const unsigned threads = std::max(1u, std::min(std::thread::hardware_concurrency(), 16u));
  auto work = [&](size_t begin, size_t end) {
    for (size_t t = begin; t < end; ++t) {
      const glm::uvec4& tri = soup.triangles[t];
      const glm::dvec3 v[3] = {grid_coords_exact(grid, soup.positions[tri.x]),
                               grid_coords_exact(grid, soup.positions[tri.y]),
                               grid_coords_exact(grid, soup.positions[tri.z])};
      int64_t first[3], last[3];
      bool empty = false;
      for (int a = 0; a < 3; ++a) {
        const double lo = std::min({v[0][a], v[1][a], v[2][a]}), hi = std::max({v[0][a], v[1][a], v[2][a]});
        // Closed boxes [k - w, k + 1 + w] meeting [lo, hi]: ceil(lo - w) - 1 <= k <= floor(hi + w).
        first[a] = int64_t(std::clamp(std::ceil(lo - widen) - 1.0, 0.0, 1e15));
        last[a] = int64_t(std::clamp(std::floor(hi + widen), -1.0, double(grid.dims[a]) - 1.0));
        empty |= first[a] > last[a];
      }
      if (empty) continue;
      for (int64_t k = first[2]; k <= last[2]; ++k)
        for (int64_t j = first[1]; j <= last[1]; ++j)
          for (int64_t i = first[0]; i <= last[0]; ++i) {
            if (!overlap_exact(v, i, j, k, widen)) continue;
            const uint64_t linear = grid.linear_index(uint32_t(i), uint32_t(j), uint32_t(k));
            std::atomic_ref<uint32_t>(out.occ[linear >> 5])
                .fetch_or(1u << (linear & 31), std::memory_order_relaxed);
          }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned w = 0; w < threads; ++w) pool.emplace_back(work, n * w / threads, n * (w + 1) / threads);
  for (std::thread& th : pool) th.join();
  for (uint32_t w : out.occ) out.voxels_set += uint64_t(std::popcount(w));
  return out;
}

}  // namespace voxr
