#include "voxelize/surface_accuracy.h"

#include <algorithm>
#include <bit>

#include "util/error.h"
#include "voxelize/reference_voxelizer.h"
#include "voxelize/snapped_triangle.h"

namespace voxr {

namespace {

int64_t floor_cell(int64_t a) {
  return a >= 0 ? a / VOXR_SUBVOXEL : -((-a + VOXR_SUBVOXEL - 1) / VOXR_SUBVOXEL);
}

}  // namespace

void count_tunnels(const VoxelGrid& result, const TriangleSoup& soup, uint64_t* crossings,
                   uint64_t* tunnels) {
  const GridSpec& grid = result.spec;
  const std::array<float, 12> m = grid.world_to_grid();
  *crossings = 0;
  *tunnels = 0;
  for (size_t tri = 0; tri < soup.triangle_count(); ++tri) {
    const SnappedTriangle t = snap_triangle(m, soup, tri);
    for (int axis = 0; axis < 3; ++axis) {
      // Cyclic permutation that makes `axis` the depth axis and keeps the handedness (and the normal).
      const int p[3] = {(axis + 1) % 3, (axis + 2) % 3, axis};
      SnappedTriangle r = t;
      for (int c = 0; c < 3; ++c)
        for (int q = 0; q < 3; ++q) r.v[c][q] = t.v[c][p[q]];
      for (int q = 0; q < 3; ++q) r.n[q] = t.n[p[q]];
      int64_t first[2], last[2];
      for (int q = 0; q < 2; ++q) {
        const int64_t lo = std::min({r.v[0][q], r.v[1][q], r.v[2][q]});
        const int64_t hi = std::max({r.v[0][q], r.v[1][q], r.v[2][q]});
        first[q] = std::max<int64_t>(0, floor_cell(lo));
        last[q] = std::min<int64_t>(int64_t(grid.dims[p[q]]) - 1, floor_cell(hi));
      }
      for (int64_t j = first[1]; j <= last[1]; ++j)
        for (int64_t i = first[0]; i <= last[0]; ++i) {
          int64_t k = 0;
          if (!reference_center_crossing(r, i, j, &k) || k < 0 || k >= int64_t(grid.dims[axis])) continue;
          int64_t cell[3];
          cell[p[0]] = i;
          cell[p[1]] = j;
          cell[p[2]] = k;
          ++*crossings;
          *tunnels += !result.occupied(uint32_t(cell[0]), uint32_t(cell[1]), uint32_t(cell[2]));
        }
    }
  }
}

SurfaceAccuracy measure_surface_accuracy(const VoxelGrid& result, const VoxelGrid& exact,
                                         const TriangleSoup& soup) {
  VOXR_CHECK(result.spec.dims == exact.spec.dims);
  SurfaceAccuracy a;
  for (size_t w = 0; w < exact.occ.size(); ++w) {
    a.exact_voxels += std::popcount(exact.occ[w]);
    a.true_positives += std::popcount(exact.occ[w] & result.occ[w]);
    a.false_positives += std::popcount(~exact.occ[w] & result.occ[w]);
    a.false_negatives += std::popcount(exact.occ[w] & ~result.occ[w]);
  }
  count_tunnels(result, soup, &a.crossings, &a.tunnels);
  return a;
}

}  // namespace voxr
