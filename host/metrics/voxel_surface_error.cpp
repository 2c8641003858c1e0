#include "metrics/voxel_surface_error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>

#include "util/error.h"

namespace voxr {

namespace {

// The point of triangle abc nearest to p (Ericson, Real-Time Collision Detection, 5.1.5).
glm::dvec3 closest_on_triangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                               const glm::dvec3& c) {
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + ab * (d1 / (d1 - d3));
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = va + vb + vc;
  if (!(denom > 0.0)) return a;  // a degenerate triangle: its first vertex
  return a + ab * (vb / denom) + ac * (vc / denom);
}

// Triangles binned into cells of kCell voxels by their bounding boxes (compressed rows), for nearest-triangle
// queries that widen ring by ring until no nearer triangle can lie in the next ring.
class TriangleBins {
 public:
  static constexpr int kCell = 4;

  TriangleBins(const std::vector<std::array<glm::dvec3, 3>>& tris, const glm::uvec3& dims) : tris_(tris) {
    cells_ = glm::ivec3((glm::ivec3(dims) + kCell - 1) / kCell);
    std::vector<std::pair<uint64_t, uint32_t>> entries;
    for (uint32_t t = 0; t < tris.size(); ++t) {
      const glm::ivec3 lo = cell_of(glm::min(glm::min(tris[t][0], tris[t][1]), tris[t][2]));
      const glm::ivec3 hi = cell_of(glm::max(glm::max(tris[t][0], tris[t][1]), tris[t][2]));
      for (int z = lo.z; z <= hi.z; ++z)
        for (int y = lo.y; y <= hi.y; ++y)
          for (int x = lo.x; x <= hi.x; ++x) entries.emplace_back(index(glm::ivec3(x, y, z)), t);
    }
    std::sort(entries.begin(), entries.end());
    start_.assign(uint64_t(cells_.x) * cells_.y * cells_.z + 1, 0);
    for (const auto& e : entries) ++start_[e.first + 1];
    for (size_t i = 1; i < start_.size(); ++i) start_[i] += start_[i - 1];
    items_.reserve(entries.size());
    for (const auto& e : entries) items_.push_back(e.second);
  }

  // Distance (grid units) from p to the nearest triangle.
  double nearest(const glm::dvec3& p) const {
    const glm::ivec3 c = cell_of(p);
    const int max_ring = std::max({cells_.x, cells_.y, cells_.z});
    double best = std::numeric_limits<double>::infinity();
    for (int r = 0; r <= max_ring; ++r) {
      for (int z = c.z - r; z <= c.z + r; ++z)
        for (int y = c.y - r; y <= c.y + r; ++y)
          for (int x = c.x - r; x <= c.x + r; ++x) {
            if (std::max({std::abs(x - c.x), std::abs(y - c.y), std::abs(z - c.z)}) != r) continue;
            if (x < 0 || y < 0 || z < 0 || x >= cells_.x || y >= cells_.y || z >= cells_.z) continue;
            const uint64_t i = index(glm::ivec3(x, y, z));
            for (uint64_t e = start_[i]; e < start_[i + 1]; ++e) {
              const auto& t = tris_[items_[e]];
              best = std::min(best, glm::length(p - closest_on_triangle(p, t[0], t[1], t[2])));
            }
          }
      // Every triangle in ring r + 1 and beyond is at least r cells from p's cell.
      if (best <= double(r) * kCell) break;
    }
    return best;
  }

 private:
  const std::vector<std::array<glm::dvec3, 3>>& tris_;
  glm::ivec3 cells_;
  std::vector<uint64_t> start_;
  std::vector<uint32_t> items_;

  glm::ivec3 cell_of(const glm::dvec3& p) const {
    const glm::ivec3 c(glm::floor(p / double(kCell)));
    return glm::clamp(c, glm::ivec3(0), cells_ - 1);
  }
  uint64_t index(const glm::ivec3& c) const { return (uint64_t(c.z) * cells_.y + c.y) * cells_.x + c.x; }
};

// Distance (grid units) from p to the nearest set voxel's closed box within kSearchVoxels, else
// kSearchVoxels.
double distance_to_set_voxel(const VoxelGrid& grid, const glm::dvec3& p) {
  const glm::ivec3 dims(grid.spec.dims);
  const glm::ivec3 v(glm::floor(p));
  double best = kSearchVoxels;
  for (int r = 0; r <= kSearchVoxels; ++r) {
    for (int z = v.z - r; z <= v.z + r; ++z)
      for (int y = v.y - r; y <= v.y + r; ++y)
        for (int x = v.x - r; x <= v.x + r; ++x) {
          if (std::max({std::abs(x - v.x), std::abs(y - v.y), std::abs(z - v.z)}) != r) continue;
          if (x < 0 || y < 0 || z < 0 || x >= dims.x || y >= dims.y || z >= dims.z) continue;
          if (!grid.occupied(uint32_t(x), uint32_t(y), uint32_t(z))) continue;
          const glm::dvec3 lo(x, y, z);
          const glm::dvec3 d = glm::max(glm::max(lo - p, p - (lo + 1.0)), glm::dvec3(0.0));
          best = std::min(best, glm::length(d));
        }
    // Voxels of ring r + 1 are at least r voxels from p.
    if (best <= double(r)) break;
  }
  return best;
}

}  // namespace

VoxelSurfaceError voxel_surface_error(const VoxelGrid& grid, const GridSpec& spec, const TriangleSoup& soup,
                                      uint32_t samples, uint64_t seed) {
  if (soup.empty()) fail("voxel surface error: the mesh has no triangles");
  if (grid.spec.dims != spec.dims || grid.occ.size() * 32 < spec.voxel_count())
    fail("voxel surface error: the grid's dimensions are not the spec's");
  // Triangles in grid units (double), positions moved from the soup's anchor to the grid's.
  const glm::dvec3 shift = soup.anchor - spec.anchor;
  const auto to_grid = [&](const glm::vec4& p) {
    return glm::dvec3(spec.to_grid(glm::vec3(glm::dvec3(p) + shift)));
  };
  std::vector<std::array<glm::dvec3, 3>> tris;
  std::vector<double> cumulative_area;
  tris.reserve(soup.triangle_count());
  double area = 0.0;
  for (const glm::uvec4& t : soup.triangles) {
    std::array<glm::dvec3, 3> v{to_grid(soup.positions[t.x]), to_grid(soup.positions[t.y]),
                                to_grid(soup.positions[t.z])};
    area += 0.5 * glm::length(glm::cross(v[1] - v[0], v[2] - v[0]));
    tris.push_back(v);
    cumulative_area.push_back(area);
  }
  const double longest = double(std::max({spec.dims.x, spec.dims.y, spec.dims.z}));
  VoxelSurfaceError e;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);

  // Surface -> voxels: points uniform by area (a mesh of zero area: its vertices).
  double sum = 0.0;
  uint64_t holes = 0;
  const double hole_distance = 0.5 * std::sqrt(3.0);
  for (uint32_t s = 0; s < samples; ++s) {
    glm::dvec3 p;
    if (area > 0.0) {
      const double a = unit(rng) * area;
      const size_t t = std::min<size_t>(
          std::lower_bound(cumulative_area.begin(), cumulative_area.end(), a) - cumulative_area.begin(),
          tris.size() - 1);
      double u = unit(rng), w = unit(rng);
      if (u + w > 1.0) u = 1.0 - u, w = 1.0 - w;
      p = tris[t][0] + u * (tris[t][1] - tris[t][0]) + w * (tris[t][2] - tris[t][0]);
    } else {
      p = tris[s % tris.size()][s % 3];
    }
    const double d = distance_to_set_voxel(grid, p);
    sum += d;
    holes += d > hole_distance;
  }
  e.surface_samples = samples;
  e.mesh_to_voxels = samples ? sum / samples / longest : 0.0;
  e.hole_share = samples ? double(holes) / samples : 0.0;

  // Voxels -> surface: every set voxel, or each with probability samples / voxels_set (a hash of its index
  // and the seed: deterministic, independent of order).
  uint64_t set = 0;
  grid.for_each_set([&](uint64_t, uint64_t) { ++set; });
  const TriangleBins bins(tris, spec.dims);
  const double keep = set > samples ? double(samples) / double(set) : 1.0;
  sum = 0.0;
  const glm::uvec3 d = spec.dims;
  grid.for_each_set([&](uint64_t linear, uint64_t) {
    if (keep < 1.0) {
      uint64_t h = (linear + seed) * 0x9e3779b97f4a7c15ull;
      h ^= h >> 29;
      h *= 0xbf58476d1ce4e5b9ull;
      h ^= h >> 32;
      if (double(h >> 11) * 0x1.0p-53 >= keep) return;
    }
    const glm::dvec3 c(double(linear % d.x) + 0.5, double((linear / d.x) % d.y) + 0.5,
                       double(linear / (uint64_t(d.x) * d.y)) + 0.5);
    sum += bins.nearest(c);
    ++e.voxel_samples;
  });
  e.voxels_to_mesh = e.voxel_samples ? sum / double(e.voxel_samples) / longest : 0.0;
  return e;
}

}  // namespace voxr
