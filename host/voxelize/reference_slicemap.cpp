#include "voxelize/reference_slicemap.h"

#include "voxelize/reference_voxelizer.h"

#include <algorithm>
#include <bit>
#include <limits>
#include <vector>

namespace voxr {

namespace {

using i128 = __int128;
constexpr int64_t S = VOXR_SUBVOXEL;

// floor(a / b), b != 0.
i128 floor_div(i128 a, i128 b) {
  if (b < 0) {
    a = -a;
    b = -b;
  }
  const i128 q = a / b;
  return q * b > a ? q - 1 : q;
}

// Calls fn(i, j, zf) for every fragment of the soup inside the grid (0 <= zf < dims.z * S).
template <typename Fn>
void for_each_fragment(const TriangleSoup& soup, const GridSpec& grid, Fn&& fn) {
  const std::array<float, 12> m = grid.world_to_grid();
  const int64_t z_end = int64_t(grid.dims.z) * S;
  for (size_t tri = 0; tri < soup.triangle_count(); ++tri) {
    const SnappedTriangle t = snap_triangle(m, soup, tri);
    int64_t first[2], last[2];
    for (int a = 0; a < 2; ++a) {
      const int64_t lo = std::min({t.v[0][a], t.v[1][a], t.v[2][a]});
      const int64_t hi = std::max({t.v[0][a], t.v[1][a], t.v[2][a]});
      first[a] = std::max<int64_t>(0, int64_t(floor_div(lo, S)) - 1);
      last[a] = std::min<int64_t>(int64_t(grid.dims[a]) - 1, int64_t(floor_div(hi, S)));
    }
    for (int64_t j = first[1]; j <= last[1]; ++j)
      for (int64_t i = first[0]; i <= last[0]; ++i) {
        const std::optional<int64_t> zf = reference_fragment_depth(t, i, j);
        if (zf && *zf >= 0 && *zf < z_end) fn(uint32_t(i), uint32_t(j), *zf);
      }
  }
}

}  // namespace

std::optional<int64_t> reference_fragment_depth(const SnappedTriangle& t, int64_t i, int64_t j) {
  if (!reference_center_covers(t, i, j)) return std::nullopt;
  const i128 nz = t.n[2];
  const i128 cx = i * S + S / 2, cy = j * S + S / 2;
  // The plane n . (p - v0) = 0 at the centre: z * nz = v0z * nz - n.x (cx - v0x) - n.y (cy - v0y).
  const i128 z_times_nz =
      i128(t.v[0][2]) * nz - i128(t.n[0]) * (cx - t.v[0][0]) - i128(t.n[1]) * (cy - t.v[0][1]);
  return int64_t(floor_div(z_times_nz, nz));
}

uint32_t reference_slicemap_bit(SlicemapSlicing slicing, int64_t zf, int64_t near, int64_t far,
                                uint32_t slices) {
  if (slicing == SlicemapSlicing::kUniform) return uint32_t(floor_div(zf, S));
  return uint32_t(floor_div(i128(zf - near) * slices, i128(far - near + 1)));
}

Slicemap reference_slicemap(const TriangleSoup& soup, const GridSpec& grid, SlicemapSlicing slicing) {
  Slicemap map;
  map.spec = grid;
  map.slicing = slicing;
  map.words_per_column = (grid.dims.z + 31) / 32;
  const uint64_t columns = uint64_t(grid.dims.x) * grid.dims.y;
  map.bits.assign(columns * map.words_per_column, 0u);
  const bool local = slicing == SlicemapSlicing::kLocal;
  std::vector<int64_t> near(columns, std::numeric_limits<int64_t>::max()), far(columns, -1);
  if (local)
    for_each_fragment(soup, grid, [&](uint32_t i, uint32_t j, int64_t zf) {
      const uint64_t c = map.column(i, j);
      near[c] = std::min(near[c], zf);
      far[c] = std::max(far[c], zf);
    });
  for_each_fragment(soup, grid, [&](uint32_t i, uint32_t j, int64_t zf) {
    const uint64_t c = map.column(i, j);
    const uint32_t b = reference_slicemap_bit(slicing, zf, near[c], far[c], grid.dims.z);
    map.bits[c * map.words_per_column + b / 32] |= 1u << (b % 32);
  });
  if (local) {
    map.near.assign(columns, Slicemap::kEmptyNear);
    map.far.assign(columns, 0);
    for (uint64_t c = 0; c < columns; ++c)
      if (far[c] >= 0) {
        map.near[c] = uint32_t(near[c]);
        map.far[c] = uint32_t(far[c]);
      }
  }
  return map;
}

VoxelGrid reference_slicemap_voxels(const Slicemap& map) {
  const GridSpec& grid = map.spec;
  VoxelGrid out;
  out.spec = grid;
  out.occ.assign((grid.voxel_count() + 31) / 32, 0u);
  const bool local = map.slicing == SlicemapSlicing::kLocal;
  for (uint32_t j = 0; j < grid.dims.y; ++j)
    for (uint32_t i = 0; i < grid.dims.x; ++i) {
      const uint64_t c = map.column(i, j);
      if (map.bits_set(i, j) == 0) continue;
      for (uint32_t k = 0; k < grid.dims.z; ++k) {
        bool set = false;
        if (!local) {
          set = map.bit(i, j, k);
        } else {
          // Depths of slab k inside the column's range, and the bits that hold them (contiguous: the bit is
          // monotone in the depth).
          const int64_t near = map.near[c], far = map.far[c];
          const int64_t lo = std::max<int64_t>(int64_t(k) * S, near);
          const int64_t hi = std::min<int64_t>(int64_t(k + 1) * S - 1, far);
          if (lo > hi) continue;
          const uint32_t b0 = reference_slicemap_bit(map.slicing, lo, near, far, grid.dims.z);
          const uint32_t b1 = reference_slicemap_bit(map.slicing, hi, near, far, grid.dims.z);
          for (uint32_t b = b0; b <= b1 && !set; ++b) set = map.bit(i, j, b);
        }
        if (!set) continue;
        const uint64_t linear = grid.linear_index(i, j, k);
        out.occ[linear >> 5] |= 1u << (linear & 31);
        ++out.voxels_set;
      }
    }
  return out;
}

}  // namespace voxr
