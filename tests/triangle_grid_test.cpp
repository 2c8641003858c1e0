// The per-voxel triangle lists (render/triangle_grid.h, the voxelizer's count -> scan -> fill -> sort)
// against a CPU reference built from the exact predicates: the kernels' own rule (the 13-axis test on the
// snapped triangle against the box widened by the snap margin, reference_voxelizer.h) gives the lists bit for
// bit, and every voxel the unsnapped input triangle touches (reference_overlap.h, double) must list it. Then
// the march through the lists (kernels/common/triangle_grid.h tg_nearest_hit) against brute force over every
// triangle with the same test, bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "core/generators.h"
#include "core/mesh_loader.h"
#include "grid/channel_table.h"
#include "render/render_scene.h"
#include "render/triangle_grid.h"
#include "test_support.h"
#include "voxelize/reference_overlap.h"
#include "voxelize/reference_voxelizer.h"
#include "voxelize/snapped_triangle.h"

namespace voxr {
namespace {

constexpr int64_t S = VOXR_SUBVOXEL;
constexpr size_t kGroup = 64;

int64_t floor_div(int64_t a, int64_t b) {
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

struct Lists {
  std::vector<uint64_t> offsets;  // per set voxel in linear order, then the total
  std::vector<uint32_t> ids;
};

// The lists by the kernels' rule, on the host: per voxel (linear order), the ascending triangle indices.
Lists reference_lists(const TriangleSoup& soup, const GridSpec& grid) {
  const int64_t margin = snap_margin(grid, soup.bounds());
  const std::array<float, 12> m = grid.world_to_grid();
  std::map<uint64_t, std::vector<uint32_t>> by_voxel;
  for (size_t t = 0; t < soup.triangle_count(); ++t) {
    const SnappedTriangle st = snap_triangle(m, soup, t);
    int64_t first[3], last[3];
    for (int a = 0; a < 3; ++a) {
      const int64_t lo = std::min({st.v[0][a], st.v[1][a], st.v[2][a]});
      const int64_t hi = std::max({st.v[0][a], st.v[1][a], st.v[2][a]});
      first[a] = std::max<int64_t>(0, floor_div(lo - margin, S) - 1);
      last[a] = std::min<int64_t>(int64_t(grid.dims[a]) - 1, floor_div(hi + margin, S));
    }
    for (int64_t k = first[2]; k <= last[2]; ++k)
      for (int64_t j = first[1]; j <= last[1]; ++j)
        for (int64_t i = first[0]; i <= last[0]; ++i)
          if (reference_conservative_overlap(st, i, j, k, margin))
            by_voxel[grid.linear_index(uint32_t(i), uint32_t(j), uint32_t(k))].push_back(uint32_t(t));
  }
  Lists lists;
  for (const auto& [voxel, ids] : by_voxel) {
    lists.offsets.push_back(lists.ids.size());
    lists.ids.insert(lists.ids.end(), ids.begin(), ids.end());  // ascending: triangles visited in order
  }
  lists.offsets.push_back(lists.ids.size());
  return lists;
}

struct DeviceLists {
  VoxelGrid grid;  // occupancy and count read back
  Lists lists;
};

DeviceLists read_lists(TriangleGrid& tg) {
  ClRuntime& cl = test::runtime();
  DeviceVoxelGrid& g = tg.grid();
  DeviceLists out;
  out.grid = read_back(cl, g);
  const uint64_t set = g.voxels_set;
  out.lists.offsets.resize(set + 1);
  cl.download(g.list_offsets.buffer, out.lists.offsets.data(), (set + 1) * 8, "download offsets");
  out.lists.ids.resize(out.lists.offsets.back());
  if (!out.lists.ids.empty())
    cl.download(g.list_ids.buffer, out.lists.ids.data(), out.lists.ids.size() * 4, "download ids");
  return out;
}

GridSpec grid_of(const TriangleSoup& soup, uint32_t resolution) {
  GridRequest request;
  request.resolution = resolution;
  return fit_grid(soup.bounds(), request, soup.anchor);
}

// Bit for bit against the kernels' rule; a superset of the input triangles' exact overlap.
void expect_lists(const TriangleSoup& soup, uint32_t resolution, const std::string& what) {
  ClRuntime& cl = test::runtime();
  Voxelizer voxelizer(cl);
  const DeviceMesh mesh(cl, soup);
  TriangleGrid tg(cl, voxelizer);
  tg.build(mesh, resolution);
  const DeviceLists actual = read_lists(tg);
  const GridSpec grid = grid_of(soup, resolution);
  ASSERT_EQ(tg.grid().spec.dims, grid.dims) << what;
  const Lists expected = reference_lists(soup, grid);
  ASSERT_GT(expected.ids.size(), soup.triangle_count()) << what;
  EXPECT_EQ(actual.grid.voxels_set + 1, expected.offsets.size()) << what;
  EXPECT_TRUE(actual.lists.offsets == expected.offsets) << what << ": offsets differ";
  EXPECT_TRUE(actual.lists.ids == expected.ids) << what << ": ids differ";
  EXPECT_EQ(tg.grid().list_capacity, expected.ids.size()) << what;

  // Every voxel the unsnapped triangle touches lists it (exact test, double).
  std::map<uint64_t, uint64_t> rank;
  {
    uint64_t r = 0;
    for (uint64_t v = 0; v < grid.voxel_count(); ++v)
      if (actual.grid.occupied(v)) rank[v] = r++;
  }
  uint64_t checked = 0, missing = 0;
  for (size_t t = 0; t < soup.triangle_count(); ++t) {
    glm::dvec3 v[3];
    for (int c = 0; c < 3; ++c) v[c] = grid_coords_exact(grid, soup.positions[soup.triangles[t][c]]);
    glm::dvec3 lo = glm::min(v[0], glm::min(v[1], v[2])), hi = glm::max(v[0], glm::max(v[1], v[2]));
    for (int64_t k = std::max<int64_t>(0, int64_t(std::floor(lo.z)) - 1);
         k <= std::min<int64_t>(grid.dims.z - 1, int64_t(std::floor(hi.z)) + 1); ++k)
      for (int64_t j = std::max<int64_t>(0, int64_t(std::floor(lo.y)) - 1);
           j <= std::min<int64_t>(grid.dims.y - 1, int64_t(std::floor(hi.y)) + 1); ++j)
        for (int64_t i = std::max<int64_t>(0, int64_t(std::floor(lo.x)) - 1);
             i <= std::min<int64_t>(grid.dims.x - 1, int64_t(std::floor(hi.x)) + 1); ++i) {
          if (!overlap_exact(v, i, j, k)) continue;
          ++checked;
          const auto it = rank.find(grid.linear_index(uint32_t(i), uint32_t(j), uint32_t(k)));
          if (it == rank.end()) {
            ++missing;
            continue;
          }
          const uint32_t* first = actual.lists.ids.data() + actual.lists.offsets[it->second];
          const uint32_t* last = actual.lists.ids.data() + actual.lists.offsets[it->second + 1];
          missing += !std::binary_search(first, last, uint32_t(t));
        }
  }
  EXPECT_GT(checked, soup.triangle_count()) << what;
  EXPECT_EQ(missing, 0u) << what << ": exact (triangle, voxel) pairs not listed";
}

TriangleSoup thin_vase() {
  VaseParams p;
  p.height = 1.4f;
  p.thickness = 0.006f;  // a wall far under a voxel at 64
  return make_vase(p);
}

TriangleSoup floor_and_object() {
  TriangleSoup soup = make_plane(glm::vec2(8.0f), 4);
  soup.append(make_uv_sphere(0.05f, 8, 12), glm::mat4(1.0f), 1);
  return soup;
}

// The same object 10^6 units from the origin (an anchor there) and far from its anchor too.
TriangleSoup far_object() {
  TriangleSoup soup = make_torus();
  soup.anchor = glm::dvec3(1.0e6, -2.0e6, 3.0e5);
  for (glm::vec4& p : soup.positions) p += glm::vec4(300.0f, -200.0f, 500.0f, 0.0f);
  return soup;
}

TEST(TriangleGrid, ListsEqualReference) {
  expect_lists(make_uv_sphere(1.0f, 16, 32), 32, "sphere");
  expect_lists(make_tree(1.0f, 3), 64, "tree");  // a bunny-like mix: a closed trunk and many small sheets
  expect_lists(thin_vase(), 64, "thin vase");
  expect_lists(floor_and_object(), 128, "floor + small object");
  expect_lists(far_object(), 48, "far from the origin");
}

TEST(TriangleGrid, BunnyListsEqualReference) {
  const std::string path = test::mesh_path("bunny.obj");
  if (path.empty()) GTEST_SKIP() << "bunny.obj missing: run scripts/fetch-meshes.sh";
  expect_lists(load_mesh(path), 64, "bunny");
}

TEST(TriangleGrid, RefusesResolutionsThatNeedSplitting) {
  ClRuntime& cl = test::runtime();
  Voxelizer voxelizer(cl);
  const TriangleSoup soup = make_box();
  const DeviceMesh mesh(cl, soup);
  TriangleGrid tg(cl, voxelizer);
  try {
    tg.build(mesh, 4096);
    FAIL() << "4096 voxels need split triangles";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("split"), std::string::npos) << e.what();
  }
}

// tg_nearest_hit through the lists equals brute force over every triangle (same test, same order).
TEST(TriangleGrid, NearestHitEqualsBruteForce) {
  ClRuntime& cl = test::runtime();
  TriangleSoup soup = thin_vase();
  // A coincident pair: a floor under the vase's bottom (opaque) against the vase's own flat bottom.
  soup.append(make_plane(glm::vec2(3.0f), 2), glm::mat4(1.0f), 1);
  soup.append(make_box(glm::vec3(-0.1f, 0.0f, -0.1f), glm::vec3(0.1f, 0.3f, 0.1f)), glm::mat4(1.0f), 0);
  std::vector<Material> materials(2);
  materials[0].kind = MaterialKind::kDielectric;
  materials[1].kind = MaterialKind::kOpaque;
  const std::vector<RenderMaterial> rm = render_materials(materials);
  cl::Buffer mats = cl.buffer(rm.size() * sizeof(RenderMaterial), "materials");
  cl.upload(mats, rm.data(), rm.size() * sizeof(RenderMaterial), "upload materials");

  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const size_t n = 4000;
  std::vector<glm::vec4> rays(n), dirs(n);
  std::vector<uint32_t> skip(n, VOXR_NO_TRIANGLE);
  for (size_t r = 0; r < n; ++r) {
    glm::vec3 o(u(rng) * 1.6f, 0.7f + u(rng) * 1.0f, u(rng) * 1.6f);
    glm::vec3 d(u(rng), u(rng), u(rng));
    if (r % 4 == 0) {  // from a triangle's centroid, skipping it
      const uint32_t t = uint32_t(rng() % soup.triangle_count());
      o = glm::vec3(soup.positions[soup.triangles[t].x] + soup.positions[soup.triangles[t].y] +
                    soup.positions[soup.triangles[t].z]) /
          3.0f;
      skip[r] = t;
    }
    if (r % 7 == 0) d = glm::vec3(0.0f, -1.0f, u(rng) * 1e-3f);  // straight down onto the coincident floor
    if (glm::length(d) < 1e-3f) d = glm::vec3(1.0f, 0.0f, 0.0f);
    rays[r] = glm::vec4(o, 0.0f);
    dirs[r] = glm::vec4(glm::normalize(d), r % 5 == 0 ? 0.5f : INFINITY);
  }
  cl::Buffer ray_buf = cl.buffer(n * 16, "rays"), dir_buf = cl.buffer(n * 16, "dirs"),
             skip_buf = cl.buffer(n * 4, "skip");
  cl.upload(ray_buf, rays.data(), n * 16, "upload rays");
  cl.upload(dir_buf, dirs.data(), n * 16, "upload dirs");
  cl.upload(skip_buf, skip.data(), n * 4, "upload skip");
  const DeviceMesh mesh(cl, soup);
  Voxelizer voxelizer(cl);
  const float coincide = 1e-5f;
  Defines d = channel_defines();
  d.push_back({"WG_SIZE", std::to_string(kGroup)});
  auto run_all = [&](std::vector<uint32_t>& tri, std::vector<glm::vec4>& th) {
    cl::Buffer tb = cl.buffer(n * 4, "tri"), hb = cl.buffer(n * 16, "th");
    cl::Kernel k = cl.kernel("triangle_grid_probe.cl", "tg_probe_all", d);
    cl.launch("probe", k, n, kGroup, mesh.positions(), mesh.triangles(), cl_uint(soup.triangle_count()), mats,
              ray_buf, dir_buf, skip_buf, cl_uint(n), coincide, tb, hb);
    tri.resize(n);
    th.resize(n);
    cl.download(tb, tri.data(), n * 4, "download");
    cl.download(hb, th.data(), n * 16, "download");
  };
  std::vector<uint32_t> want_tri;
  std::vector<glm::vec4> want_th;
  run_all(want_tri, want_th);
  size_t hits = 0, coincident_floor = 0;
  for (size_t r = 0; r < n; ++r) {
    hits += want_tri[r] != VOXR_NO_TRIANGLE;
    coincident_floor += r % 7 == 0 && want_tri[r] != VOXR_NO_TRIANGLE && soup.triangles[want_tri[r]].w == 1;
  }
  EXPECT_GT(hits, n / 3);
  EXPECT_GT(coincident_floor, 0u);
  for (uint32_t resolution : {8u, 37u, 128u}) {
    TriangleGrid tg(cl, voxelizer);
    tg.build(mesh, resolution);
    cl::Buffer tb = cl.buffer(n * 4, "tri"), hb = cl.buffer(n * 16, "th");
    cl::Kernel k = cl.kernel("triangle_grid_probe.cl", "tg_probe_grid", d);
    cl.launch("probe", k, n, kGroup, tg.view_args(), mats, ray_buf, dir_buf, skip_buf, cl_uint(n), coincide,
              tb, hb);
    std::vector<uint32_t> tri(n);
    std::vector<glm::vec4> th(n);
    cl.download(tb, tri.data(), n * 4, "download");
    cl.download(hb, th.data(), n * 16, "download");
    size_t differ = 0;
    for (size_t r = 0; r < n; ++r) {
      const bool same = tri[r] == want_tri[r] && (tri[r] == VOXR_NO_TRIANGLE || th[r] == want_th[r]);
      if (!same && differ++ < 5)
        ADD_FAILURE() << "res " << resolution << " ray " << r << ": grid " << tri[r] << " t " << th[r].x
                      << ", brute force " << want_tri[r] << " t " << want_th[r].x;
    }
    EXPECT_EQ(differ, 0u) << "resolution " << resolution;
  }
}

}  // namespace
}  // namespace voxr
