// Writing the sparse grid: every format from a SparseVoxelGrid gives the bytes its dense grid gives; the .vdb
// read back with OpenVDB's own reader equals the grid voxel for voxel and value for value; the .npz read by
// NumPy (python3) equals it too; a failed write (missing plugin, full disk) leaves nothing.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "core/generators.h"
#include "grid/sparse_voxel_grid.h"
#include "io/grid_encoding.h"
#include "io/nrrd_writer.h"
#include "io/openvdb_module.h"
#include "io/volume_writer.h"
#include "test_support.h"
#include "util/error.h"
#include "voxelize/voxelizer.h"

#ifdef VOXR_TEST_OPENVDB
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#endif

namespace voxr {
namespace {

using test::listing;
using test::slurp;

namespace fs = std::filesystem;

// A torus voxelized with every surface channel on a grid whose dims are not multiples of 8 (bricks stick
// out of the grid), optionally in a rotated frame.
VoxelGrid torus_grid(uint32_t res, bool rotated) {
  TriangleSoup soup = make_torus(1.0f, 0.4f, 24, 16);
  GridSpec spec = test::fitted(soup, res);
  if (rotated) {
    // Same grid, rotated 30 degrees about z (the torus stays inside the fitted box well enough for a test).
    const float c = std::cos(0.5236f), s = std::sin(0.5236f);
    spec.axes = glm::mat3(glm::vec3(c, s, 0.0f), glm::vec3(-s, c, 0.0f), glm::vec3(0.0f, 0.0f, 1.0f));
  }
  for (size_t t = 0; t < soup.triangles.size(); ++t) soup.triangles[t].w = uint32_t(t % 5);  // materials
  soup.colors.vertex_rgba.resize(soup.positions.size());  // colours from positions, alpha varying too
  for (size_t v = 0; v < soup.positions.size(); ++v) {
    const glm::vec4 p = soup.positions[v];
    soup.colors.vertex_rgba[v] =
        uint32_t(int(p.x * 90.0f + 128.0f) & 255) | uint32_t(int(p.y * 90.0f + 128.0f) & 255) << 8 |
        uint32_t(int(p.z * 200.0f + 128.0f) & 255) << 16 | uint32_t(128 + v % 128) << 24;
  }
  Voxelizer voxelizer(test::runtime());
  VoxelizeOptions options;
  options.channels = ChannelSet::parse("occ,count,normal,material,color");
  return voxelizer.run(soup, spec, options);
}

// Writes `dense` and to_sparse(dense) under `dir` as `name` and expects the same files, byte for byte.
void expect_same_files(const VoxelGrid& dense, const fs::path& dir, const std::string& name) {
  const SparseVoxelGrid sparse = to_sparse(dense);
  fs::create_directories(dir / "dense");
  fs::create_directories(dir / "sparse");
  const std::vector<fs::path> a = write_volume(dense, dir / "dense" / name);
  const std::vector<fs::path> b = write_volume(sparse, dir / "sparse" / name);
  ASSERT_EQ(a.size(), b.size()) << name;
  for (size_t f = 0; f < a.size(); ++f) {
    EXPECT_EQ(a[f].filename(), b[f].filename());
    const std::string x = slurp(a[f]), y = slurp(b[f]);
    EXPECT_GT(x.size(), 0u);
    EXPECT_TRUE(x == y) << a[f] << " and " << b[f] << " differ (" << x.size() << " and " << y.size()
                        << " bytes)";
  }
}

TEST(SparseWriters, EveryFormatFromSparseIsByteIdentical) {
  const test::TempDir folder;
  const VoxelGrid g = torus_grid(45, false);
  ASSERT_GT(g.voxels_set, 1000u);
  ASSERT_NE(g.spec.dims.x % 8, 0u);
  for (const char* name : {"t.nrrd", "t.vti", "t.vox"}) expect_same_files(g, folder.path(), name);
  // binvox: cubic grids.
  TriangleSoup soup = make_torus();
  GridRequest r;
  r.dims = glm::uvec3(37);
  Voxelizer voxelizer(test::runtime());
  const VoxelGrid cube = voxelizer.run(soup, fit_grid(soup.bounds(), r, soup.anchor), VoxelizeOptions{});
  expect_same_files(cube, folder.path(), "c.binvox");
}

TEST(SparseWriters, RotatedGridAndNormalsFromSums) {
  const test::TempDir folder;
  VoxelGrid g = torus_grid(30, true);
  for (const char* name : {"r.nrrd", "r.vti"}) expect_same_files(g, folder.path(), name);
  g.normal.clear();  // the writers normalize normal_sum themselves
  for (const char* name : {"s.nrrd", "s.vti"}) expect_same_files(g, folder.path(), name);
}

TEST(SparseWriters, SlicesLargerThanAChunkStreamByRows) {
  // 1100 x 1000 voxels per slice > kDenseChunk: a slice is written in row ranges.
  const test::TempDir folder;
  GridSpec spec;
  spec.dims = {1100, 1000, 10};  // slices 5 and 9 lie in the upper half of a brick layer
  VoxelGrid g;
  g.spec = spec;
  g.occ.assign(size_t((spec.voxel_count() + 31) / 32), 0u);
  for (const uint32_t k : {0u, 5u, 9u})
    for (uint32_t j = 0; j < 1000; j += 37)
      for (uint32_t i = k; i < 1100; i += 101) {
        const uint64_t l = spec.linear_index(i, j, k);
        g.occ[l >> 5] |= 1u << (l & 31);
        ++g.voxels_set;
      }
  g.channels = ChannelSet::parse("occ,count");
  g.for_each_set([&](uint64_t linear, uint64_t) { g.count.push_back(uint32_t(linear % 1000 + 1)); });
  ASSERT_GT(uint64_t(spec.dims.x) * spec.dims.y, kDenseChunk);
  expect_same_files(g, folder.path(), "w.nrrd");
}

#ifdef VOXR_TEST_OPENVDB
TEST(SparseWriters, VdbReadsBackWithOpenVDB) {
  if (!openvdb_module_available()) GTEST_SKIP() << "the OpenVDB plugin is not built";
  const test::TempDir folder;
  for (const bool rotated : {false, true}) {
    const VoxelGrid dense = torus_grid(40, rotated);
    const SparseVoxelGrid g = to_sparse(dense);
    const fs::path out = folder.path() / (rotated ? "r.vdb" : "t.vdb");
    EXPECT_EQ(write_volume(g, out), std::vector<fs::path>{out});
    EXPECT_EQ(listing(folder.path()).count(out.filename().string()), 1u);

    openvdb::initialize();
    openvdb::io::File file(out.string());
    file.open();
    EXPECT_EQ(file.getMetadata()->metaValue<std::string>("creator"), "voxr");
    const openvdb::GridPtrVecPtr grids = file.getGrids();
    file.close();
    ASSERT_EQ(grids->size(), 6u);
    auto named = [&](const std::string& name) {
      for (const auto& grid : *grids)
        if (grid->getName() == name) return grid;
      return openvdb::GridBase::Ptr();
    };
    const auto occ = openvdb::gridPtrCast<openvdb::BoolGrid>(named("occupancy"));
    const auto count = openvdb::gridPtrCast<openvdb::Int32Grid>(named("count"));
    const auto normal = openvdb::gridPtrCast<openvdb::Vec3SGrid>(named("normal"));
    const auto material = openvdb::gridPtrCast<openvdb::Int32Grid>(named("material"));
    const auto color = openvdb::gridPtrCast<openvdb::Vec3SGrid>(named("color"));
    const auto alpha = openvdb::gridPtrCast<openvdb::FloatGrid>(named("alpha"));
    ASSERT_TRUE(occ && count && normal && material && color && alpha);
    const openvdb::Vec3i dims = occ->metaValue<openvdb::Vec3i>("voxr_dims");
    EXPECT_EQ(dims, openvdb::Vec3i(int(g.spec.dims.x), int(g.spec.dims.y), int(g.spec.dims.z)));
    // One leaf per brick, every set voxel active with its values, nothing else active.
    EXPECT_EQ(occ->tree().leafCount(), g.bricks());
    for (const auto& grid : *grids) EXPECT_EQ(grid->activeVoxelCount(), g.voxels_set) << grid->getName();
    const NormalChannel nc(g);
    const auto occ_acc = occ->getConstAccessor();
    const auto count_acc = count->getConstAccessor();
    const auto normal_acc = normal->getConstAccessor();
    const auto material_acc = material->getConstAccessor();
    const auto color_acc = color->getConstAccessor();
    const auto alpha_acc = alpha->getConstAccessor();
    uint64_t checked = 0;
    g.for_each_set([&](uint32_t i, uint32_t j, uint32_t k, uint64_t r) {
      const openvdb::Coord c{int(i), int(j), int(k)};
      ASSERT_TRUE(occ_acc.isValueOn(c) && occ_acc.getValue(c)) << i << "," << j << "," << k;
      EXPECT_EQ(uint32_t(count_acc.getValue(c)), g.count[r]);
      EXPECT_EQ(uint32_t(material_acc.getValue(c)), g.material[r]);
      const uint32_t rgba = g.color[r];
      EXPECT_EQ(color_acc.getValue(c),
                openvdb::Vec3s(float(rgba & 255u) / 255.0f, float((rgba >> 8) & 255u) / 255.0f,
                               float((rgba >> 16) & 255u) / 255.0f));
      EXPECT_EQ(alpha_acc.getValue(c), float(rgba >> 24) / 255.0f);
      const glm::vec3 n = nc(r);
      EXPECT_EQ(normal_acc.getValue(c), openvdb::Vec3s(n.x, n.y, n.z));
      // The transform puts index (i, j, k) at the voxel's world centre.
      const openvdb::Vec3d w = occ->indexToWorld(c);
      const glm::dvec3 e = g.spec.voxel_center_absolute(i, j, k);
      EXPECT_NEAR(w.x(), e.x, 1e-5);
      EXPECT_NEAR(w.y(), e.y, 1e-5);
      EXPECT_NEAR(w.z(), e.z, 1e-5);
      ++checked;
    });
    EXPECT_EQ(checked, g.voxels_set);
    EXPECT_NEAR(occ->voxelSize().x(), g.spec.voxel_size, 1e-7);
    EXPECT_EQ(occ->transform(), normal->transform());
    EXPECT_EQ(normal->getVectorType(), openvdb::VEC_COVARIANT_NORMALIZE);
  }
}
#endif

TEST(SparseWriters, NpzReadsBackWithNumpy) {
  if (std::system("/usr/bin/python3 -c 'import numpy' >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "python3 with numpy is not installed";
  const test::TempDir folder;
  const VoxelGrid dense = torus_grid(20, true);
  const SparseVoxelGrid g = to_sparse(dense);
  const fs::path out = folder.path() / "t.npz", json = folder.path() / "t.json";
  write_volume(g, out);
  // NumPy reads the archive; the arrays go back as JSON (doubles print exactly).
  const std::string script = fmt::format(
      "import json, numpy as np\n"
      "z = np.load('{}')\n"
      "json.dump({{k: {{'dtype': str(z[k].dtype), 'shape': list(z[k].shape), 'values': z[k].tolist()}} "
      "for k in z.files}}, open('{}', 'w'))\n",
      out.string(), json.string());
  std::ofstream(folder.path() / "read.py") << script;
  ASSERT_EQ(std::system(fmt::format("/usr/bin/python3 {}", (folder.path() / "read.py").string()).c_str()), 0);
  const nlohmann::json z = nlohmann::json::parse(slurp(json));
  const uint64_t n = g.voxels_set;
  EXPECT_EQ(z["ijk"]["dtype"], "int32");
  EXPECT_EQ(z["ijk"]["shape"], nlohmann::json({n, 3}));
  EXPECT_EQ(z["count"]["dtype"], "uint32");
  EXPECT_EQ(z["normal"]["dtype"], "float32");
  EXPECT_EQ(z["normal"]["shape"], nlohmann::json({n, 3}));
  EXPECT_EQ(z["material"]["dtype"], "uint32");
  EXPECT_EQ(z["color"]["dtype"], "uint8");
  EXPECT_EQ(z["color"]["shape"], nlohmann::json({n, 4}));
  EXPECT_EQ(z["dims"]["values"], nlohmann::json({g.spec.dims.x, g.spec.dims.y, g.spec.dims.z}));
  EXPECT_EQ(z["voxel_size"]["shape"], nlohmann::json::array());
  EXPECT_EQ(z["voxel_size"]["values"].get<double>(), double(g.spec.voxel_size));
  const glm::dvec3 o = g.spec.voxel_center_absolute(0, 0, 0);
  EXPECT_EQ(z["origin"]["values"], nlohmann::json({o.x, o.y, o.z}));
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(z["axes"]["values"][a][c].get<double>(), double(g.spec.axes[a][c]));
  const NormalChannel nc(g);
  uint64_t row = 0;
  g.for_each_set([&](uint32_t i, uint32_t j, uint32_t k, uint64_t r) {
    ASSERT_EQ(z["ijk"]["values"][row], nlohmann::json({i, j, k})) << row;
    EXPECT_EQ(z["count"]["values"][row].get<uint32_t>(), g.count[r]);
    EXPECT_EQ(z["material"]["values"][row].get<uint32_t>(), g.material[r]);
    for (int q = 0; q < 4; ++q)
      EXPECT_EQ(z["color"]["values"][row][q].get<uint32_t>(), (g.color[r] >> (8 * q)) & 255u) << row;
    const glm::vec3 nv = nc(r);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(z["normal"]["values"][row][c].get<float>(), nv[c]);
    ++row;
  });
  EXPECT_EQ(row, n);
}

// Restores an environment variable when it goes.
struct ScopedEnv {
  std::string name;
  std::optional<std::string> old;
  ScopedEnv(const char* n, const char* value) : name(n) {
    if (const char* v = std::getenv(n)) old = v;
    setenv(n, value, 1);
  }
  ~ScopedEnv() {
    if (old)
      setenv(name.c_str(), old->c_str(), 1);
    else
      unsetenv(name.c_str());
  }
};

void expect_error_naming(const SparseVoxelGrid& g, const fs::path& out, const std::string& also) {
  try {
    write_volume(g, out);
    ADD_FAILURE() << "no error writing " << out;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(out.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(also), std::string::npos) << e.what();
  }
}

TEST(SparseWriters, MissingPluginLeavesNothing) {
  const test::TempDir folder;
  const SparseVoxelGrid g = to_sparse(torus_grid(16, false));
  const ScopedEnv env("VOXR_OPENVDB_PLUGIN", (folder.path() / "libnothing.so").c_str());
  expect_error_naming(g, folder.path() / "t.vdb", "OpenVDB plugin");
  try {
    check_volume_output(folder.path() / "t.vdb", g.spec.dims);
    ADD_FAILURE() << "check_volume_output accepted .vdb without the plugin";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("t.vdb"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(listing(folder.path()).empty());
}

TEST(SparseWriters, FullDiskLeavesNothing) {
  // A file size limit makes writes fail part way through, as a full disk would.
  const test::TempDir folder;
  const SparseVoxelGrid g = to_sparse(torus_grid(40, false));
  rlimit old{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  const auto old_handler = ::signal(SIGXFSZ, SIG_IGN);
  rlimit small = old;
  small.rlim_cur = 4096;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  expect_error_naming(g, folder.path() / "t.npz", "t.npz");
  expect_error_naming(g, folder.path() / "t.vti", "write failed");
  if (openvdb_module_available()) {
    const ScopedEnv env("VOXR_VDB_COMPRESSION", "none");
    expect_error_naming(g, folder.path() / "t.vdb", "OpenVDB could not write");
  }
  ::setrlimit(RLIMIT_FSIZE, &old);
  ::signal(SIGXFSZ, old_handler);
  EXPECT_TRUE(listing(folder.path()).empty());
}

}  // namespace
}  // namespace voxr
