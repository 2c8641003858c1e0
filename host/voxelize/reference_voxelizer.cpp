#include "voxelize/reference_voxelizer.h"

#include <algorithm>
#include <map>

#include "vox_color.h"
#include "voxelize/device_colors.h"
#include "voxelize/grid_params.h"

namespace voxr {

namespace {

using i128 = __int128;
constexpr int64_t S = VOXR_SUBVOXEL;

int64_t floor_div(int64_t a, int64_t b) {
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

}  // namespace

bool reference_conservative_overlap(const SnappedTriangle& t, int64_t i, int64_t j, int64_t k,
                                    int64_t margin) {
  // Akenine-Moller's formulation around the box centre, in doubled coordinates so the centre is integral:
  // centre c = 2*corner + S, half-size h = S + 2 margin, vertices 2v.
  const int64_t corner[3] = {i * S, j * S, k * S};
  i128 p[3][3];
  for (int c = 0; c < 3; ++c)
    for (int a = 0; a < 3; ++a) p[c][a] = i128(2 * t.v[c][a]) - (2 * corner[a] + S);
  auto separated = [&](const i128 axis[3]) {
    i128 proj[3];
    for (int c = 0; c < 3; ++c) proj[c] = axis[0] * p[c][0] + axis[1] * p[c][1] + axis[2] * p[c][2];
    const i128 lo = std::min({proj[0], proj[1], proj[2]});
    const i128 hi = std::max({proj[0], proj[1], proj[2]});
    i128 r = 0;
    for (int a = 0; a < 3; ++a) r += (axis[a] < 0 ? -axis[a] : axis[a]) * (S + 2 * margin);
    return lo > r || hi < -r;
  };
  // Box face normals.
  for (int a = 0; a < 3; ++a) {
    i128 axis[3] = {0, 0, 0};
    axis[a] = 1;
    if (separated(axis)) return false;
  }
  // Triangle normal.
  {
    const i128 n[3] = {t.n[0], t.n[1], t.n[2]};
    if (separated(n)) return false;
  }
  // Edge x box-axis cross products.
  for (int e = 0; e < 3; ++e) {
    const int f = (e + 1) % 3;
    const i128 d[3] = {t.v[f][0] - t.v[e][0], t.v[f][1] - t.v[e][1], t.v[f][2] - t.v[e][2]};
    const i128 axes[3][3] = {{0, d[2], -d[1]}, {-d[2], 0, d[0]}, {d[1], -d[0], 0}};
    for (const auto& axis : axes)
      if (separated(axis)) return false;
  }
  return true;
}

bool reference_center_covers(const SnappedTriangle& t, int64_t i, int64_t j) {
  const i128 nz = t.n[2];
  if (nz == 0) return false;  // edge-on: the projection covers no centre
  const i128 cx = i * S + S / 2, cy = j * S + S / 2;
  // Counter-clockwise order of the projected vertices.
  const int order[3] = {0, nz > 0 ? 1 : 2, nz > 0 ? 2 : 1};
  for (int e = 0; e < 3; ++e) {
    const auto& a = t.v[order[e]];
    const auto& b = t.v[order[(e + 1) % 3]];
    const i128 dx = b[0] - a[0], dy = b[1] - a[1];
    const i128 w = dx * (cy - a[1]) - dy * (cx - a[0]);
    const bool top_left = dy < 0 || (dy == 0 && dx < 0);
    if (w < 0 || (w == 0 && !top_left)) return false;
  }
  return true;
}

bool reference_center_crossing(const SnappedTriangle& t, int64_t i, int64_t j, int64_t* k) {
  if (!reference_center_covers(t, i, j)) return false;
  const i128 nz = t.n[2];
  const i128 cx = i * S + S / 2, cy = j * S + S / 2;
  // The plane's depth at the centre is z = v0z + num / nz, so z * nz = v0z * nz + num; the cell is
  // floor(z / S) = floor(z_times_nz / (nz * S)).
  const i128 num = -(i128(t.n[0]) * (cx - t.v[0][0]) + i128(t.n[1]) * (cy - t.v[0][1]));
  i128 top = i128(t.v[0][2]) * nz + num, bottom = nz * S;
  if (bottom < 0) {
    top = -top;
    bottom = -bottom;
  }
  *k = int64_t(top >= 0 ? top / bottom : -((-top + bottom - 1) / bottom));
  return true;
}

bool reference_center_hit(const SnappedTriangle& t, int64_t i, int64_t j, int64_t k) {
  int64_t cell = 0;
  return reference_center_crossing(t, i, j, &cell) && cell == k;
}

VoxelGrid reference_voxelize(const TriangleSoup& soup, const GridSpec& grid, RasterMode mode,
                             ChannelSet channels) {
  const std::array<float, 12> m = grid.world_to_grid();
  const int64_t margin = mode == RasterMode::kConservative ? snap_margin(grid, soup.bounds()) : 0;
  struct Attr {
    uint32_t count = 0;
    glm::ivec3 nsum{0};
    uint32_t material = 0;
    uint64_t rgba[4] = {0, 0, 0, 0};  // colour component sums
  };
  std::map<uint64_t, Attr> voxels;
  // Colour: the device's tables and sample (kernels/common/vox_color.h), summed as the kernels do.
  const bool colored = channels.has(Channel::kColor);
  const ColorTables tables = colored ? color_tables(soup.colors, "the mesh") : ColorTables{};
  const VoxGridParams params = make_grid_params(grid, uint32_t(soup.triangle_count()), uint32_t(margin));
  for (size_t tri = 0; tri < soup.triangle_count(); ++tri) {
    const SnappedTriangle t = snap_triangle(m, soup, tri);
    const std::array<int32_t, 3> n = fixed_normal(t);
    VoxColorTri color{};
    if (colored) {
      vox_color_geometry(&color, t.v[0][0], t.v[0][1], t.v[0][2], t.v[1][0], t.v[1][1], t.v[1][2], t.v[2][0],
                         t.v[2][1], t.v[2][2]);
      const glm::uvec4& idx = soup.triangles[tri];
      vox_color_fetch(&color, tables.params, idx.x, idx.y, idx.z, uint32_t(tri),
                      soup.colors.vertex_rgba.data(),
                      reinterpret_cast<const float*>(soup.colors.vertex_uv.data()),
                      soup.colors.triangle_look.data(), tables.looks.data());
    }
    int64_t first[3], last[3];
    for (int a = 0; a < 3; ++a) {
      const int64_t lo = std::min({t.v[0][a], t.v[1][a], t.v[2][a]});
      const int64_t hi = std::max({t.v[0][a], t.v[1][a], t.v[2][a]});
      first[a] = std::max<int64_t>(0, floor_div(lo - margin, S) - 1);
      last[a] = std::min<int64_t>(int64_t(grid.dims[a]) - 1, floor_div(hi + margin, S));
    }
    for (int64_t k = first[2]; k <= last[2]; ++k)
      for (int64_t j = first[1]; j <= last[1]; ++j)
        for (int64_t i = first[0]; i <= last[0]; ++i) {
          const bool hit = mode == RasterMode::kConservative
                               ? reference_conservative_overlap(t, i, j, k, margin)
                               : reference_center_hit(t, i, j, k);
          if (!hit) continue;
          Attr& v = voxels[grid.linear_index(uint32_t(i), uint32_t(j), uint32_t(k))];
          v.count += 1;
          v.nsum += glm::ivec3(n[0], n[1], n[2]);
          v.material = std::max(v.material, t.material);
          if (colored) {
            const uint32_t rgba = vox_color_sample(&color, vox_voxel_centre(&params, int(i), int(j), int(k)),
                                                   tables.texels.data());
            for (int q = 0; q < 4; ++q) v.rgba[q] += (rgba >> (8 * q)) & 255u;
          }
        }
  }
  VoxelGrid out;
  out.spec = grid;
  out.channels = channels;
  out.occ.assign((grid.voxel_count() + 31) / 32, 0u);
  out.voxels_set = voxels.size();
  for (const auto& [linear, v] : voxels) {
    out.occ[linear >> 5] |= 1u << (linear & 31);
    if (channels.has(Channel::kCount)) out.count.push_back(v.count);
    if (channels.has(Channel::kNormal)) {
      out.normal_sum.push_back(v.nsum);
      const float len = glm::length(glm::vec3(v.nsum));
      out.normal.push_back(len > 0.0f ? glm::vec3(v.nsum) / len : glm::vec3(0.0f));
    }
    if (channels.has(Channel::kMaterial)) out.material.push_back(v.material);
    if (colored)
      out.color.push_back(
          vox_color_mean(long(v.rgba[0] + (v.rgba[1] << 32)), long(v.rgba[2] + (v.rgba[3] << 32)), v.count));
  }
  return out;
}

}  // namespace voxr
