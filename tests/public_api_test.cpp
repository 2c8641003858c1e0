// The public C++ API (include/voxr/voxr.h) against the internals it wraps: arrays and files give the voxels
// the Voxelizer gives for the same soup, dense and sparse layouts agree, the accessors agree with each other,
// and bad input throws voxr::Error with one line.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "core/grid_spec.h"
#include "core/mesh_loader.h"
#include "test_support.h"
#include "voxelize/voxelizer.h"
#include "voxr/voxr.h"

namespace voxr::test {
namespace {

// A tilted box: 8 vertices, 12 triangles, materials 0..2 by face pair, odd-looking numbers.
struct ArrayMesh {
  std::vector<double> positions;
  std::vector<uint32_t> triangles, materials;
  MeshView view() const { return {positions, triangles, materials, "box"}; }
};

ArrayMesh tilted_box() {
  ArrayMesh m;
  const double c = std::cos(0.3), s = std::sin(0.3);
  for (int v = 0; v < 8; ++v) {
    const double x = (v & 1) ? 1.7 : -0.4, y = (v & 2) ? 0.9 : -1.1, z = (v & 4) ? 2.3 : 0.2;
    m.positions.insert(m.positions.end(), {c * x - s * y + 100.25, s * x + c * y, z});
  }
  const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (int f = 0; f < 6; ++f) {
    const uint32_t* q = quads[f];
    m.triangles.insert(m.triangles.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
    m.materials.insert(m.materials.end(), {uint32_t(f / 2), uint32_t(f / 2)});
  }
  return m;
}

std::string ply_text(const ArrayMesh& m) {
  std::string s = fmt::format(
      "ply\nformat ascii 1.0\nelement vertex {}\nproperty double x\nproperty double y\nproperty double "
      "z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
      m.positions.size() / 3, m.triangles.size() / 3);
  for (size_t i = 0; i < m.positions.size(); i += 3)
    s += fmt::format("{} {} {}\n", m.positions[i], m.positions[i + 1], m.positions[i + 2]);
  for (size_t i = 0; i < m.triangles.size(); i += 3)
    s += fmt::format("3 {} {} {}\n", m.triangles[i], m.triangles[i + 1], m.triangles[i + 2]);
  return s;
}

std::vector<uint8_t> occupancy(const VoxelVolume& v) {
  const auto d = v.dims();
  std::vector<uint8_t> out(size_t(d[0]) * d[1] * d[2]);
  v.occupancy(out);
  return out;
}

std::vector<uint32_t> indices(const VoxelVolume& v) {
  std::vector<uint32_t> out(3 * v.voxels_set());
  v.occupied_indices(out);
  return out;
}

template <typename Fn>
void expect_error(Fn&& fn, const std::string& part) {
  try {
    fn();
    ADD_FAILURE() << "no voxr::Error; expected one containing '" << part << "'";
  } catch (const voxr::Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(part), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

TEST(PublicApi, ArraysEqualTheVoxelizerOnTheSameSoup) {
  const ArrayMesh m = tilted_box();
  VoxelizeSettings settings;
  settings.resolution = 37;
  settings.channels = "occ,count,normal,material";
  Context context;
  const VoxelVolume v = context.voxelize(m.view(), settings);

  const TriangleSoup soup = soup_from_arrays(m.positions, m.triangles, m.materials, "box");
  GridRequest request;
  request.resolution = 37;
  const GridSpec grid = fit_grid(soup.bounds(), request, soup.anchor);
  VoxelizeOptions options;
  options.channels = ChannelSet::parse("occ,count,normal,material");
  const VoxelGrid expected = Voxelizer(runtime()).run(soup, grid, options);

  ASSERT_EQ(v.dims(), (std::array<uint32_t, 3>{grid.dims.x, grid.dims.y, grid.dims.z}));
  ASSERT_EQ(v.voxels_set(), expected.voxels_set);
  ASSERT_GT(v.voxels_set(), 100u);
  const std::vector<uint8_t> occ = occupancy(v);
  for (uint64_t i = 0; i < grid.voxel_count(); ++i) ASSERT_EQ(occ[i], expected.occupied(i) ? 1 : 0) << i;
  EXPECT_TRUE(std::equal(v.count().begin(), v.count().end(), expected.count.begin(), expected.count.end()));
  EXPECT_TRUE(std::equal(v.material().begin(), v.material().end(), expected.material.begin(),
                         expected.material.end()));
  ASSERT_EQ(v.normal().size(), 3 * expected.normal.size());
  for (size_t i = 0; i < expected.normal.size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(v.normal()[3 * i + c], expected.normal[i][c]);
  EXPECT_EQ(v.channels(), "occ,count,normal,material");
  EXPECT_FALSE(v.sparse());

  // index_to_world puts voxel (i, j, k)'s corner where the grid does.
  const std::array<double, 16> m4 = v.index_to_world();
  const glm::dvec3 corner = grid.anchor + glm::dvec3(grid.origin);
  EXPECT_DOUBLE_EQ(m4[12], corner.x);
  EXPECT_DOUBLE_EQ(m4[0], double(grid.voxel_size));
  EXPECT_DOUBLE_EQ(v.voxel_size(), double(grid.voxel_size));
  const glm::dvec3 centre = grid.voxel_center_absolute(3, 4, 5);
  for (int r = 0; r < 3; ++r)
    EXPECT_NEAR(m4[r] * 3.5 + m4[4 + r] * 4.5 + m4[8 + r] * 5.5 + m4[12 + r], centre[r], 1e-9) << r;
}

TEST(PublicApi, AFileOfTheSameNumbersGivesTheSameVoxels) {
  const ArrayMesh m = tilted_box();
  TempDir dir;
  const auto ply = dir.write("box.ply", ply_text(m));
  VoxelizeSettings settings;
  settings.resolution = 29;
  settings.channels = "occ,count,normal";
  settings.solid = "parity";
  const VoxelVolume a = voxelize(m.view(), settings);
  const VoxelVolume b = voxelize_file(ply.string(), settings);
  EXPECT_EQ(a.dims(), b.dims());
  EXPECT_EQ(occupancy(a), occupancy(b));
  EXPECT_GT(a.inside_voxels(), 0u);
  std::vector<uint8_t> ia(occupancy(a).size()), ib(ia.size());
  a.inside(ia);
  b.inside(ib);
  EXPECT_EQ(ia, ib);
  EXPECT_TRUE(std::equal(a.count().begin(), a.count().end(), b.count().begin(), b.count().end()));
}

// A mesh file's own material ids (OBJ usemtl) reach the material channel, as the arrays' ids do (until
// 2026-12-02 a bare mesh file's triangles were all given scene material 0 before voxelizing).
TEST(PublicApi, FileMaterialIdsReachTheMaterialChannel) {
  TempDir dir;
  const auto obj =
      dir.write("two.obj",
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nusemtl a\nf 1 3 2\nf 1 2 4\nusemtl b\nf 1 4 3\n"
                "f 2 3 4\n");
  VoxelizeSettings settings;
  settings.resolution = 8;
  settings.channels = "occ,material";
  const VoxelVolume v = voxelize_file(obj.string(), settings);
  const std::set<uint32_t> ids(v.material().begin(), v.material().end());
  EXPECT_EQ(ids, (std::set<uint32_t>{0, 1}));

  const std::vector<double> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const std::vector<uint32_t> triangles = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}, materials = {0, 0, 1, 1};
  const VoxelVolume a = voxelize(MeshView{positions, triangles, materials, "two"}, settings);
  EXPECT_EQ(occupancy(a), occupancy(v));
  EXPECT_TRUE(std::equal(a.material().begin(), a.material().end(), v.material().begin(), v.material().end()));
}

TEST(PublicApi, SparseAndDenseLayoutsListTheSameVoxels) {
  const ArrayMesh m = tilted_box();
  VoxelizeSettings settings;
  settings.resolution = 45;
  settings.channels = "occ,count,material";
  settings.layout = "dense";
  const VoxelVolume dense = voxelize(m.view(), settings);
  settings.layout = "sparse";
  const VoxelVolume sparse = voxelize(m.view(), settings);
  EXPECT_TRUE(sparse.sparse());
  EXPECT_EQ(occupancy(dense), occupancy(sparse));
  // Row r of occupied_indices is the voxel channel entry r belongs to, in either order.
  const auto d = dense.dims();
  auto by_voxel = [&](const VoxelVolume& v) {
    std::map<uint64_t, std::pair<uint32_t, uint32_t>> out;
    const std::vector<uint32_t> ijk = indices(v);
    for (size_t r = 0; r < v.voxels_set(); ++r)
      out[(uint64_t(ijk[3 * r + 2]) * d[1] + ijk[3 * r + 1]) * d[0] + ijk[3 * r]] = {v.count()[r],
                                                                                     v.material()[r]};
    return out;
  };
  EXPECT_EQ(by_voxel(dense), by_voxel(sparse));
  // Every listed voxel is occupied.
  const std::vector<uint8_t> occ = occupancy(dense);
  const std::vector<uint32_t> ijk = indices(dense);
  for (size_t r = 0; r < dense.voxels_set(); ++r)
    ASSERT_EQ(occ[(uint64_t(ijk[3 * r + 2]) * d[1] + ijk[3 * r + 1]) * d[0] + ijk[3 * r]], 1);
}

TEST(PublicApi, SaveWritesByExtension) {
  const ArrayMesh m = tilted_box();
  TempDir dir;
  VoxelizeSettings settings;
  settings.resolution = 16;
  const VoxelVolume v = voxelize(m.view(), settings);
  const std::vector<std::string> written = v.save((dir.path() / "box.vti").string());
  ASSERT_EQ(written.size(), 1u);
  EXPECT_GT(fs::file_size(written[0]), 100u);
  expect_error([&] { v.save((dir.path() / "box.xyz").string()); }, "box.xyz");
  expect_error([&] { v.save((dir.path() / "box.binvox").string()); }, "box.binvox");  // not cubic
}

TEST(PublicApi, BadInputThrowsOneLine) {
  ArrayMesh m = tilted_box();
  VoxelizeSettings settings;
  settings.resolution = 8;
  auto with = [&](auto change) {
    VoxelizeSettings s = settings;
    change(s);
    return s;
  };
  expect_error([&] { voxelize(m.view(), with([](auto& s) { s.method = "magic"; })); }, "magic");
  expect_error([&] { voxelize(m.view(), with([](auto& s) { s.mode = "edges"; })); }, "edges");
  expect_error([&] { voxelize(m.view(), with([](auto& s) { s.channels = "occ,smell"; })); }, "smell");
  expect_error([&] { voxelize(m.view(), with([](auto& s) { s.layout = "tight"; })); }, "tight");
  expect_error([&] { voxelize(m.view(), with([](auto& s) { s.solid = "maybe"; })); }, "maybe");
  expect_error([&] { voxelize(m.view(), with([](auto& s) { s.memory_budget = "lots"; })); }, "memory_budget");
  expect_error([&] { voxelize(m.view(), with([](auto& s) {
                                s.dims = std::array<uint32_t, 3>{4, 0, 4};
                              })); },
               "dims");
  expect_error(
      [&] { voxelize(m.view(), with([](auto& s) { s.bounds = std::array<double, 6>{0, 0, 0, 1, -1, 1}; })); },
      "bounds");
  expect_error([&] { voxelize_file("/nonexistent/mesh.obj", settings); }, "/nonexistent/mesh.obj");
  expect_error([&] { Context("no such device 12345"); }, "no such device 12345");

  ArrayMesh bad = m;
  bad.triangles[4] = 8;
  expect_error([&] { voxelize(bad.view(), settings); }, "vertex 8");
  bad = m;
  bad.positions[5] = std::numeric_limits<double>::quiet_NaN();
  expect_error([&] { voxelize(bad.view(), settings); }, "not finite");
  bad = m;
  bad.positions.pop_back();
  expect_error([&] { voxelize(bad.view(), settings); }, "triples");
  bad = m;
  bad.materials.pop_back();
  expect_error([&] { voxelize(bad.view(), settings); }, "material ids");
  bad = m;
  bad.triangles.clear();
  expect_error([&] { voxelize(bad.view(), settings); }, "no triangles");

  const VoxelVolume v = voxelize(m.view(), settings);
  std::vector<uint8_t> small(3);
  expect_error([&] { v.occupancy(small); }, "occupancy");
}

}  // namespace
}  // namespace voxr::test
