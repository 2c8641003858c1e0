#include "voxelize/reference_inside.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <deque>
#include <map>
#include <numbers>
#include <optional>
#include <thread>

#include "util/error.h"
#include "voxelize/reference_voxelizer.h"
#include "voxelize/snapped_triangle.h"
#include "voxelize/triangle_splitter.h"

namespace voxr {

namespace {

using i128 = __int128;
constexpr int64_t S = VOXR_SUBVOXEL;

i128 floor_div(i128 a, i128 b) {  // b > 0
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}
i128 ceil_div(i128 a, i128 b) {
  return -floor_div(-a, b);
}

// The kernels' input: the soup with oversized triangles split (see triangle_splitter.h).
TriangleSoup solid_input(const TriangleSoup& soup, const GridSpec& grid) {
  std::optional<TriangleSoup> pieces = split_oversized_triangles(soup, grid, nullptr, SplitCull::kColumns);
  return pieces ? std::move(*pieces) : soup;
}

std::vector<SnappedTriangle> snapped_triangles(const TriangleSoup& soup, const GridSpec& grid) {
  const std::array<float, 12> m = grid.world_to_grid();
  std::vector<SnappedTriangle> out;
  out.reserve(soup.triangle_count());
  for (size_t t = 0; t < soup.triangle_count(); ++t) out.push_back(snap_triangle(m, soup, t));
  return out;
}

// Whether the column centre (cx, cy), perturbed to (cx + e, cy - e^2) for an infinitesimal e > 0, lies
// strictly inside the triangle's xy projection. Exactly the kernels' top-left rule, written as the
// perturbation it is: each edge's orientation test falls back to the sign of -dy, then of -dx, when the
// centre is on the edge.
bool perturbed_centre_inside(const SnappedTriangle& t, int64_t cx, int64_t cy) {
  if (t.n[2] == 0) return false;
  const int s = t.n[2] > 0 ? 1 : -1;
  for (int e = 0; e < 3; ++e) {
    const auto& u = t.v[e];
    const auto& w = t.v[(e + 1) % 3];
    const i128 dx = w[0] - u[0], dy = w[1] - u[1];
    const i128 orient = dx * (cy - u[1]) - dy * (cx - u[0]);
    const i128 sign = orient != 0 ? orient : (dy != 0 ? -dy : -dx);
    if ((sign > 0 ? 1 : -1) != s) return false;
  }
  return true;
}

// Inclusive range of column centres (c + 1/2) * S within [lo, hi], clamped to [0, n).
void centre_range(const SnappedTriangle& t, int axis, uint32_t n, int64_t* first, int64_t* last) {
  const int64_t lo = std::min({t.v[0][axis], t.v[1][axis], t.v[2][axis]});
  const int64_t hi = std::max({t.v[0][axis], t.v[1][axis], t.v[2][axis]});
  *first = std::max<int64_t>(0, int64_t(ceil_div(lo - S / 2, S)));
  *last = std::min<int64_t>(int64_t(n) - 1, int64_t(floor_div(hi - S / 2, S)));
}

std::vector<uint32_t> pack_bits(const std::vector<uint8_t>& bytes) {
  std::vector<uint32_t> bits((bytes.size() + 31) / 32, 0u);
  for (size_t l = 0; l < bytes.size(); ++l)
    if (bytes[l]) bits[l >> 5] |= 1u << (l & 31);
  return bits;
}

// Late filling's repair of the questionable columns (see vox_solid_repair.cl for the rule), one column and
// voxel at a time. Returns the number of rounds that resolved a column.
uint64_t repair_columns(const GridSpec& grid, const std::vector<uint8_t>& questionable,
                        std::vector<uint8_t>& inside) {
  const int64_t nx = grid.dims.x, ny = grid.dims.y, nz = grid.dims.z;
  constexpr uint64_t kOpen = ~uint64_t(0);
  std::vector<uint64_t> level(size_t(nx * ny));
  for (size_t c = 0; c < level.size(); ++c) level[c] = questionable[c] ? kOpen : 0;
  auto at = [&](int64_t i, int64_t j, int64_t k) -> uint8_t& {
    return inside[size_t((k * ny + j) * nx + i)];
  };
  uint64_t rounds = 0;
  for (uint64_t r = 1;; ++r) {
    std::vector<std::pair<int64_t, std::vector<uint8_t>>> fresh;
    for (int64_t j = 0; j < ny; ++j)
      for (int64_t i = 0; i < nx; ++i) {
        if (level[size_t(j * nx + i)] != kOpen) continue;
        std::vector<std::pair<int64_t, int64_t>> voters;
        const int64_t nb[4][2] = {{i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}};
        for (const auto& q : nb)
          if (q[0] >= 0 && q[0] < nx && q[1] >= 0 && q[1] < ny && level[size_t(q[1] * nx + q[0])] < r)
            voters.push_back({q[0], q[1]});
        if (voters.empty()) continue;
        std::vector<uint8_t> column(static_cast<size_t>(nz));
        for (int64_t k = 0; k < nz; ++k) {
          size_t votes = 0;
          for (const auto& [vi, vj] : voters) votes += at(vi, vj, k);
          column[size_t(k)] = 2 * votes >= voters.size();  // majority, ties inside
        }
        fresh.push_back({j * nx + i, std::move(column)});
      }
    if (fresh.empty()) break;
    ++rounds;
    for (auto& [c, column] : fresh) {
      level[size_t(c)] = r;
      for (int64_t k = 0; k < nz; ++k) at(c % nx, c / nx, k) = column[size_t(k)];
    }
  }
  return rounds;
}

// Flood fill of the outside from the free border voxels over `surface`; inside = not outside.
std::vector<uint8_t> flood_inside(const GridSpec& grid, const VoxelGrid& surface) {
  const int64_t nx = grid.dims.x, ny = grid.dims.y, nz = grid.dims.z;
  const uint64_t n = grid.voxel_count();
  std::vector<uint8_t> outside(n, 0);
  std::deque<uint64_t> queue;
  auto visit = [&](int64_t i, int64_t j, int64_t k) {
    if (i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz) return;
    const uint64_t l = grid.linear_index(uint32_t(i), uint32_t(j), uint32_t(k));
    if (outside[l] || surface.occupied(l)) return;
    outside[l] = 1;
    queue.push_back(l);
  };
  for (int64_t k = 0; k < nz; ++k)
    for (int64_t j = 0; j < ny; ++j)
      for (int64_t i = 0; i < nx; ++i)
        if (i == 0 || j == 0 || k == 0 || i == nx - 1 || j == ny - 1 || k == nz - 1) visit(i, j, k);
  while (!queue.empty()) {
    const uint64_t l = queue.front();
    queue.pop_front();
    const int64_t i = int64_t(l % uint64_t(nx)), j = int64_t(l / uint64_t(nx) % uint64_t(ny)),
                  k = int64_t(l / uint64_t(nx * ny));
    visit(i - 1, j, k);
    visit(i + 1, j, k);
    visit(i, j - 1, k);
    visit(i, j + 1, k);
    visit(i, j, k - 1);
    visit(i, j, k + 1);
  }
  for (uint8_t& o : outside) o = !o;
  return outside;
}

}  // namespace

std::vector<uint32_t> reference_inside_exact(const TriangleSoup& soup, const GridSpec& grid) {
  const std::vector<SnappedTriangle> tris = snapped_triangles(solid_input(soup, grid), grid);
  const int64_t nx = grid.dims.x, ny = grid.dims.y, nz = grid.dims.z;
  // Candidate triangles per column: those whose projection's bounding box holds the column centre.
  std::vector<std::vector<uint32_t>> bins(size_t(nx * ny));
  for (size_t t = 0; t < tris.size(); ++t) {
    int64_t i0, i1, j0, j1;
    centre_range(tris[t], 0, grid.dims.x, &i0, &i1);
    centre_range(tris[t], 1, grid.dims.y, &j0, &j1);
    for (int64_t j = j0; j <= j1; ++j)
      for (int64_t i = i0; i <= i1; ++i) bins[size_t(j * nx + i)].push_back(uint32_t(t));
  }
  std::vector<uint8_t> inside(grid.voxel_count(), 0);
  std::vector<const SnappedTriangle*> hits;
  for (int64_t j = 0; j < ny; ++j)
    for (int64_t i = 0; i < nx; ++i) {
      const int64_t cx = i * S + S / 2, cy = j * S + S / 2;
      hits.clear();
      for (uint32_t t : bins[size_t(j * nx + i)])
        if (perturbed_centre_inside(tris[t], cx, cy)) hits.push_back(&tris[t]);
      for (int64_t k = 0; k < nz; ++k) {
        const int64_t cz = k * S + S / 2;
        // The crossing lies strictly above the centre C iff n . (C - v0) = n_z (cz - zc) has the sign of
        // -n_z.
        bool odd = false;
        for (const SnappedTriangle* t : hits) {
          const i128 side = i128(t->n[0]) * (cx - t->v[0][0]) + i128(t->n[1]) * (cy - t->v[0][1]) +
                            i128(t->n[2]) * (cz - t->v[0][2]);
          if (t->n[2] > 0 ? side < 0 : side > 0) odd = !odd;
        }
        inside[size_t((k * ny + j) * nx + i)] = odd;
      }
    }
  return pack_bits(inside);
}

namespace {

// Sum over `tris` of the signed solid angles (Van Oosterom & Strackee) they subtend at every voxel centre, in
// grid units, double precision; every hardware thread, one slice at a time. fn(linear, omega) gets the sums.
template <typename Fn>
void for_each_solid_angle(const std::vector<SnappedTriangle>& tris, const GridSpec& grid, Fn&& fn) {
  std::vector<std::array<double, 9>> v(tris.size());
  for (size_t t = 0; t < tris.size(); ++t)
    for (int c = 0; c < 3; ++c)
      for (int a = 0; a < 3; ++a) v[t][size_t(3 * c + a)] = double(tris[t].v[c][a]) / double(S);
  const uint32_t nx = grid.dims.x, ny = grid.dims.y, nz = grid.dims.z;
  std::atomic<uint32_t> next_slice{0};
  auto work = [&] {
    for (uint32_t k; (k = next_slice++) < nz;)
      for (uint32_t j = 0; j < ny; ++j)
        for (uint32_t i = 0; i < nx; ++i) {
          const double p[3] = {i + 0.5, j + 0.5, k + 0.5};
          double omega = 0.0;
          for (const auto& q : v) {
            double a[3], b[3], c[3];
            for (int d = 0; d < 3; ++d) {
              a[d] = q[size_t(d)] - p[d];
              b[d] = q[size_t(3 + d)] - p[d];
              c[d] = q[size_t(6 + d)] - p[d];
            }
            const double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
            const double lb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
            const double lc = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
            const double det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                               a[2] * (b[0] * c[1] - b[1] * c[0]);
            const double ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            const double ac = a[0] * c[0] + a[1] * c[1] + a[2] * c[2];
            const double bc = b[0] * c[0] + b[1] * c[1] + b[2] * c[2];
            omega += 2.0 * std::atan2(det, la * lb * lc + ab * lc + ac * lb + bc * la);
          }
          fn(grid.linear_index(i, j, k), omega);
        }
  };
  const unsigned threads = std::max(1u, std::min(std::thread::hardware_concurrency(), nz));
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
}

// Signed crossings of the +z ray from every voxel centre with `tris` (perturbed as in reference_inside_exact,
// +1 where the triangle's normal points up): the winding number of a closed oriented chain.
std::vector<int32_t> ray_winding(const std::vector<SnappedTriangle>& tris, const GridSpec& grid) {
  const int64_t nx = grid.dims.x, ny = grid.dims.y, nz = grid.dims.z;
  std::vector<std::vector<uint32_t>> bins(size_t(nx * ny));
  for (size_t t = 0; t < tris.size(); ++t) {
    int64_t i0, i1, j0, j1;
    centre_range(tris[t], 0, grid.dims.x, &i0, &i1);
    centre_range(tris[t], 1, grid.dims.y, &j0, &j1);
    for (int64_t j = j0; j <= j1; ++j)
      for (int64_t i = i0; i <= i1; ++i) bins[size_t(j * nx + i)].push_back(uint32_t(t));
  }
  std::vector<int32_t> winding(grid.voxel_count(), 0);
  for (int64_t j = 0; j < ny; ++j)
    for (int64_t i = 0; i < nx; ++i) {
      const int64_t cx = i * S + S / 2, cy = j * S + S / 2;
      for (uint32_t t : bins[size_t(j * nx + i)]) {
        const SnappedTriangle& tri = tris[t];
        if (!perturbed_centre_inside(tri, cx, cy)) continue;
        for (int64_t k = 0; k < nz; ++k) {
          const int64_t cz = k * S + S / 2;
          const i128 side = i128(tri.n[0]) * (cx - tri.v[0][0]) + i128(tri.n[1]) * (cy - tri.v[0][1]) +
                            i128(tri.n[2]) * (cz - tri.v[0][2]);
          if (tri.n[2] > 0 ? side < 0 : side > 0)
            winding[size_t((k * ny + j) * nx + i)] += tri.n[2] > 0 ? 1 : -1;
        }
      }
    }
  return winding;
}

bool degenerate(const SnappedTriangle& t) {
  return t.n[0] == 0 && t.n[1] == 0 && t.n[2] == 0;
}

}  // namespace

std::vector<uint32_t> reference_inside_winding(const TriangleSoup& soup, const GridSpec& grid,
                                               double threshold) {
  // The mesh M plus a cone C from one lattice point over M's boundary (as an oriented chain: directed edges
  // that do not cancel) is a closed chain, so sum_M omega = 4 pi winding(M + C) - sum_C omega: an exact
  // signed ray count plus solid angles of the few cone triangles. Zero-area triangles subtend no solid angle
  // and are left out of M.
  std::vector<SnappedTriangle> tris;
  for (const SnappedTriangle& t : snapped_triangles(solid_input(soup, grid), grid))
    if (!degenerate(t)) tris.push_back(t);
  using Vertex = std::array<int64_t, 3>;
  std::map<std::pair<Vertex, Vertex>, int64_t> net;  // (a, b) with a < b: uses a->b minus uses b->a
  for (const SnappedTriangle& t : tris)
    for (int e = 0; e < 3; ++e) {
      const Vertex a = t.v[size_t(e)], b = t.v[size_t((e + 1) % 3)];
      if (a < b)
        net[{a, b}] += 1;
      else if (b < a)
        net[{b, a}] -= 1;
    }
  std::vector<std::pair<Vertex, Vertex>> boundary;  // directed edges a -> b, repeated by multiplicity
  std::array<i128, 3> sum{0, 0, 0};
  for (const auto& [edge, m] : net)
    for (int64_t q = 0; q < (m < 0 ? -m : m); ++q) {
      boundary.push_back(m > 0 ? edge : std::make_pair(edge.second, edge.first));
      for (int a = 0; a < 3; ++a) sum[size_t(a)] += edge.first[size_t(a)] + edge.second[size_t(a)];
    }
  std::vector<SnappedTriangle> cone;
  if (!boundary.empty()) {
    Vertex apex;
    for (int a = 0; a < 3; ++a)
      apex[size_t(a)] = int64_t(floor_div(sum[size_t(a)], i128(2 * boundary.size())));
    for (const auto& [a, b] : boundary) {  // (apex, b, a): the cone's boundary cancels M's
      SnappedTriangle t;
      t.v = {apex, b, a};
      int64_t e0[3], e1[3];
      for (int d = 0; d < 3; ++d) {
        e0[d] = t.v[1][size_t(d)] - t.v[0][size_t(d)];
        e1[d] = t.v[2][size_t(d)] - t.v[0][size_t(d)];
      }
      t.n = {e0[1] * e1[2] - e0[2] * e1[1], e0[2] * e1[0] - e0[0] * e1[2], e0[0] * e1[1] - e0[1] * e1[0]};
      if (!degenerate(t)) cone.push_back(t);
    }
  }
  std::vector<SnappedTriangle> closed = tris;
  closed.insert(closed.end(), cone.begin(), cone.end());
  const std::vector<int32_t> winding = ray_winding(closed, grid);
  std::vector<uint8_t> inside(grid.voxel_count(), 0);
  for (uint64_t l = 0; l < inside.size(); ++l) inside[l] = std::abs(double(winding[l])) > threshold;
  if (!cone.empty())
    for_each_solid_angle(cone, grid, [&](uint64_t l, double omega) {
      inside[l] = std::abs(double(winding[l]) - omega / (4.0 * std::numbers::pi)) > threshold;
    });
  return pack_bits(inside);
}

std::vector<uint32_t> reference_inside_winding_direct(const TriangleSoup& soup, const GridSpec& grid,
                                                      double threshold) {
  const std::vector<SnappedTriangle> tris = snapped_triangles(solid_input(soup, grid), grid);
  std::vector<uint8_t> inside(grid.voxel_count(), 0);
  for_each_solid_angle(tris, grid, [&](uint64_t l, double omega) {
    inside[l] = std::abs(omega / (4.0 * std::numbers::pi)) > threshold;
  });
  return pack_bits(inside);
}

ReferenceSolid reference_solid(const TriangleSoup& soup, const GridSpec& grid, SolidMode mode) {
  const TriangleSoup input = solid_input(soup, grid);
  ReferenceSolid out;
  if (mode == SolidMode::kFlood) {
    const VoxelGrid surface = reference_voxelize(input, grid, RasterMode::kConservative, ChannelSet{});
    out.inside = pack_bits(flood_inside(grid, surface));
    return out;
  }
  const std::vector<SnappedTriangle> tris = snapped_triangles(input, grid);
  const int64_t nx = grid.dims.x, ny = grid.dims.y, nz = grid.dims.z;
  std::vector<uint8_t> toggles(grid.voxel_count(), 0), odd(size_t(nx * ny), 0);
  for (const SnappedTriangle& t : tris) {
    if (t.n[2] == 0) continue;
    int64_t i0, i1, j0, j1;
    centre_range(t, 0, grid.dims.x, &i0, &i1);
    centre_range(t, 1, grid.dims.y, &j0, &j1);
    const i128 N = t.n[2] > 0 ? t.n[2] : -i128(t.n[2]);
    for (int64_t j = j0; j <= j1; ++j)
      for (int64_t i = i0; i <= i1; ++i) {
        const int64_t cx = i * S + S / 2, cy = j * S + S / 2;
        if (!perturbed_centre_inside(t, cx, cy)) continue;
        // Crossing depth zc = Z / N (fixed point): n . (P - v0) = 0 at P = (cx, cy, zc).
        i128 Z =
            i128(t.v[0][2]) * t.n[2] - (i128(t.n[0]) * (cx - t.v[0][0]) + i128(t.n[1]) * (cy - t.v[0][1]));
        if (t.n[2] < 0) Z = -Z;
        const i128 k = mode == SolidMode::kXor ? floor_div(Z, S * N)                // slab [k, k+1) holds zc
                                               : ceil_div(Z - (S / 2) * N, S * N);  // first centre >= zc
        odd[size_t(j * nx + i)] ^= 1;
        const int64_t kt = int64_t(std::max<i128>(k, 0));
        if (kt < nz) toggles[size_t((kt * ny + j) * nx + i)] ^= 1;
      }
  }
  std::vector<uint8_t> inside(grid.voxel_count(), 0);
  for (int64_t j = 0; j < ny; ++j)
    for (int64_t i = 0; i < nx; ++i) {
      uint8_t acc = 0;
      const bool clear = mode == SolidMode::kLate && odd[size_t(j * nx + i)];
      for (int64_t k = 0; k < nz; ++k) {
        const size_t l = size_t((k * ny + j) * nx + i);
        acc ^= toggles[l];
        inside[l] = clear ? 0 : acc;
      }
    }
  if (mode == SolidMode::kLate) {
    for (uint8_t q : odd) out.questionable_columns += q;
    out.repair_iterations = repair_columns(grid, odd, inside);
  }
  out.inside = pack_bits(inside);
  return out;
}

uint64_t count_bits(std::span<const uint32_t> bits) {
  uint64_t n = 0;
  for (uint32_t w : bits) n += uint64_t(std::popcount(w));
  return n;
}

SolidError compare_bits(std::span<const uint32_t> result, std::span<const uint32_t> reference_bits,
                        std::span<const uint32_t> shell) {
  VOXR_CHECK_EQ(result.size(), reference_bits.size());
  if (!shell.empty()) VOXR_CHECK_EQ(shell.size(), result.size());
  SolidError e;
  for (size_t w = 0; w < result.size(); ++w) {
    const uint32_t counted = shell.empty() ? ~0u : ~shell[w];
    e.missing += uint64_t(std::popcount(reference_bits[w] & ~result[w] & counted));
    e.extra += uint64_t(std::popcount(result[w] & ~reference_bits[w] & counted));
  }
  return e;
}

SolidError compare_inside(const VoxelGrid& grid, std::span<const uint32_t> reference_bits) {
  return compare_bits(grid.inside, reference_bits);
}

SolidError compare_inside(const VoxelGrid& grid, std::span<const uint32_t> reference_bits,
                          std::span<const uint32_t> shell) {
  return compare_bits(grid.inside, reference_bits, shell);
}

}  // namespace voxr
