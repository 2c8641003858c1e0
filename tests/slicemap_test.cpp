// The slicemap baseline (Eisemann & Decoret 2006): kernels against the exact CPU reference (raw bits, local
// depth ranges and voxels, both slicings), uniform slicing against the slice voxelizer's centre mode, and
// designed scenes that show where local slicing differs from uniform.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>

#include <fmt/format.h>

#include "core/generators.h"
#include "core/mesh_loader.h"
#include "test_support.h"
#include "voxelize/reference_slicemap.h"
#include "voxelize/slicemap_voxelizer.h"
#include "voxelize/voxelizer.h"

namespace voxr {
namespace {

constexpr SlicemapSlicing kBoth[] = {SlicemapSlicing::kUniform, SlicemapSlicing::kLocal};

// Quad [0, w] x [0, h] at height z (two triangles).
void add_plane(TriangleSoup& soup, float w, float h, float z) {
  const uint32_t base = uint32_t(soup.positions.size());
  for (glm::vec2 p : {glm::vec2(0, 0), glm::vec2(w, 0), glm::vec2(w, h), glm::vec2(0, h)})
    soup.positions.push_back(glm::vec4(p, z, 1.0f));
  soup.triangles.push_back({base, base + 1, base + 2, 0});
  soup.triangles.push_back({base, base + 2, base + 3, 0});
}

// Empty when equal, else the number of differing words/ranges and the first few.
std::string compare_slicemaps(const Slicemap& expected, const Slicemap& actual) {
  if (expected.bits.size() != actual.bits.size()) return "sizes differ";
  std::string report;
  size_t differences = 0;
  const uint32_t dx = expected.spec.dims.x;
  auto note = [&](uint64_t column, const std::string& what) {
    if (differences++ < 8) report += fmt::format("  column ({}, {}): {}\n", column % dx, column / dx, what);
  };
  for (uint64_t w = 0; w < expected.bits.size(); ++w)
    if (expected.bits[w] != actual.bits[w])
      note(w / expected.words_per_column,
           fmt::format("word {} {:08x} vs {:08x}", w % expected.words_per_column, expected.bits[w],
                       actual.bits[w]));
  if (expected.near != actual.near || expected.far != actual.far) {
    if (expected.near.size() != actual.near.size()) return report + "depth range sizes differ";
    for (uint64_t c = 0; c < expected.near.size(); ++c)
      if (expected.near[c] != actual.near[c] || expected.far[c] != actual.far[c])
        note(c, fmt::format("range [{}, {}] vs [{}, {}]", expected.near[c], expected.far[c], actual.near[c],
                            actual.far[c]));
  }
  return differences ? fmt::format("{} differences:\n{}", differences, report) : std::string();
}

// One slicemap voxelization through the Voxelizer, with its raw bits.
struct SlicemapRun {
  VoxelGrid grid;
  Slicemap map;
  VoxelizeStats stats;
};

SlicemapRun run_slicemap(const TriangleSoup& soup, const GridSpec& grid, SlicemapSlicing slicing,
                         uint64_t record_budget_bytes = VoxelizeOptions{}.record_budget_bytes) {
  Voxelizer voxelizer(test::runtime());
  VoxelizeOptions options;
  options.method = VoxelizeMethod::kSlicemap;
  options.slicing = slicing;
  options.record_budget_bytes = record_budget_bytes;
  SlicemapRun run;
  run.grid = voxelizer.run(soup, grid, options, &run.stats);
  run.map = static_cast<SlicemapVoxelizer&>(voxelizer.surface(VoxelizeMethod::kSlicemap)).read_slicemap();
  return run;
}

// Kernels == CPU reference, bits and voxels; returns the kernels' grid.
VoxelGrid expect_exact(const TriangleSoup& soup, const GridSpec& grid, SlicemapSlicing slicing,
                       const std::string& what,
                       uint64_t record_budget_bytes = VoxelizeOptions{}.record_budget_bytes,
                       VoxelizeStats* stats = nullptr) {
  const SlicemapRun run = run_slicemap(soup, grid, slicing, record_budget_bytes);
  const Slicemap& actual_map = run.map;
  const VoxelGrid& actual = run.grid;
  if (stats) *stats = run.stats;
  const Slicemap expected_map = reference_slicemap(soup, grid, slicing);
  const VoxelGrid expected = reference_slicemap_voxels(expected_map);
  const std::string where = what + " " + slicemap_slicing_name(slicing);
  EXPECT_GT(expected_map.bits_set(), 0u) << where;
  EXPECT_EQ(compare_slicemaps(expected_map, actual_map), "") << where;
  EXPECT_EQ(test::compare_grids(expected, actual), "") << where;
  EXPECT_EQ(actual.voxels_set, expected.voxels_set) << where;
  return actual;
}

// Uniform slicemap == the slice voxelizer in centre mode (occ), kernel against kernel.
void expect_uniform_equals_center(const TriangleSoup& soup, const GridSpec& grid, const std::string& what) {
  Voxelizer slice(test::runtime());
  VoxelizeOptions options;
  options.mode = RasterMode::kCenter;
  const VoxelGrid center = slice.run(soup, grid, options);
  const VoxelGrid uniform = run_slicemap(soup, grid, SlicemapSlicing::kUniform).grid;
  EXPECT_GT(center.voxels_set, 0u) << what;
  EXPECT_EQ(test::compare_grids(center, uniform), "") << what;
}

TEST(Slicemap, ProceduralMeshesEqualReference) {
  const std::pair<const char*, TriangleSoup> meshes[] = {{"torus", make_torus()},
                                                         {"sphere", make_uv_sphere(1.0f, 16, 32)}};
  for (const auto& [name, soup] : meshes)
    for (SlicemapSlicing s : kBoth) expect_exact(soup, test::fitted(soup, 64), s, name);
}

TEST(Slicemap, RandomSoupsEqualReference) {
  // Small and large triangles; a grid that crops the soup (fragments outside [0, Z) and columns outside the
  // grid are dropped) and a non-cubic one with dims.z not a multiple of 32.
  const TriangleSoup small = test::random_soup(21, 400, -1.0f, 1.0f, 0.3f);
  const TriangleSoup large = test::random_soup(22, 60, -1.0f, 1.0f, 2.0f);
  GridRequest crop;
  crop.bounds = Bounds{{-0.6f, -0.7f, -0.5f}, {0.8f, 0.6f, 0.4f}};
  crop.resolution = 40;
  GridSpec flat = test::fitted(small, 48);
  flat.dims.z = 37;
  for (SlicemapSlicing s : kBoth) {
    expect_exact(small, test::fitted(small, 48), s, "small");
    expect_exact(large, test::fitted(large, 40), s, "large");
    expect_exact(small, fit_grid({}, crop), s, "cropped small");
    expect_exact(large, fit_grid({}, crop), s, "cropped large");
    expect_exact(small, flat, s, "non-cubic");
  }
}

TEST(Slicemap, BunnyEqualsReference) {
  const std::string path = test::mesh_path("bunny.obj");
  if (path.empty()) GTEST_SKIP() << "bunny.obj missing: run scripts/fetch-meshes.sh";
  const TriangleSoup soup = load_mesh(path);
  for (SlicemapSlicing s : kBoth) expect_exact(soup, test::fitted(soup, 96), s, "bunny");
}

TEST(Slicemap, UniformEqualsSliceVoxelizerCenter) {
  expect_uniform_equals_center(make_torus(), test::fitted(make_torus(), 96), "torus");
  expect_uniform_equals_center(make_uv_sphere(1.0f, 16, 32), test::fitted(make_uv_sphere(1.0f, 16, 32), 80),
                               "sphere");
  const TriangleSoup soup = test::random_soup(23, 500, -1.0f, 1.0f, 0.8f);
  expect_uniform_equals_center(soup, test::fitted(soup, 64), "random");
  const std::string path = test::mesh_path("bunny.obj");
  if (path.empty()) GTEST_SKIP() << "bunny.obj missing: run scripts/fetch-meshes.sh";
  const TriangleSoup bunny = load_mesh(path);
  expect_uniform_equals_center(bunny, test::fitted(bunny, 160), "bunny");
}

TEST(Slicemap, LocalResolvesSurfacesCloserThanAVoxel) {
  // Two parallel sheets half a voxel apart inside slab 10 of 32: uniform slicing merges them into one bit
  // per column; local slicing spreads the column's 32 bits over [near, far] = [2624, 2752] (10.25 and 10.75
  // times 256) and puts them at bits 0 and 31. Both bits lie in voxel 10, so the voxel grids agree.
  TriangleSoup soup;
  add_plane(soup, 16, 16, 10.25f);
  add_plane(soup, 16, 16, 10.75f);
  const GridSpec grid = test::unit_grid({16, 16, 32});
  const SlicemapRun uniform_run = run_slicemap(soup, grid, SlicemapSlicing::kUniform);
  const SlicemapRun local_run = run_slicemap(soup, grid, SlicemapSlicing::kLocal);
  const Slicemap &uniform = uniform_run.map, &local = local_run.map;
  const VoxelGrid &uniform_grid = uniform_run.grid, &local_grid = local_run.grid;
  for (uint32_t j = 0; j < 16; ++j)
    for (uint32_t i = 0; i < 16; ++i) {
      ASSERT_EQ(uniform.bits_set(i, j), 1u);
      ASSERT_TRUE(uniform.bit(i, j, 10));
      ASSERT_EQ(local.bits_set(i, j), 2u);
      ASSERT_TRUE(local.bit(i, j, 0) && local.bit(i, j, 31));
      ASSERT_EQ(local.near[local.column(i, j)], 2624u);
      ASSERT_EQ(local.far[local.column(i, j)], 2752u);
    }
  EXPECT_EQ(uniform.bits_set(), 256u);
  EXPECT_EQ(local.bits_set(), 512u);
  EXPECT_EQ(uniform_grid.voxels_set, 256u);
  EXPECT_EQ(test::compare_grids(uniform_grid, local_grid), "");
  for (SlicemapSlicing s : kBoth) expect_exact(soup, grid, s, "sheets");
}

TEST(Slicemap, LocalBitStraddlingAVoxelFaceAddsAVoxel) {
  // Three sheets at z = 1.25, 3.9, 5.75 in an 8-slice grid: uniform sets voxels 1, 3, 5 of every column.
  // Local: near = 320, far = 1472, W = 1153; the middle depth 998 falls in bit floor(678 * 8 / 1153) = 4,
  // which holds depths [320 + 577, 320 + 721) = [897, 1041): voxels 3 and 4. So local adds voxel 4 to
  // each of the 256 columns (bits 0 and 7 stay inside voxels 1 and 5).
  TriangleSoup soup;
  for (float z : {1.25f, 3.9f, 5.75f}) add_plane(soup, 16, 16, z);
  const GridSpec grid = test::unit_grid({16, 16, 8});
  const VoxelGrid uniform_grid = run_slicemap(soup, grid, SlicemapSlicing::kUniform).grid;
  const SlicemapRun local_run = run_slicemap(soup, grid, SlicemapSlicing::kLocal);
  const Slicemap& local = local_run.map;
  const VoxelGrid& local_grid = local_run.grid;
  EXPECT_EQ(uniform_grid.voxels_set, 3u * 256u);
  EXPECT_EQ(local_grid.voxels_set, 4u * 256u);
  for (uint32_t j = 0; j < 16; ++j)
    for (uint32_t i = 0; i < 16; ++i) {
      ASSERT_EQ(local.bits_set(i, j), 3u);
      ASSERT_TRUE(local.bit(i, j, 0) && local.bit(i, j, 4) && local.bit(i, j, 7));
      for (uint32_t k = 0; k < 8; ++k) {
        ASSERT_EQ(uniform_grid.occupied(i, j, k), k == 1 || k == 3 || k == 5);
        ASSERT_EQ(local_grid.occupied(i, j, k), k == 1 || k == 3 || k == 4 || k == 5);
      }
    }
  for (SlicemapSlicing s : kBoth) expect_exact(soup, grid, s, "three sheets");
}

TEST(Slicemap, LocalContainsUniformOnATorus) {
  // Every fragment's local bit holds its own depth, so local's voxels contain uniform's; the extra voxels
  // are the neighbours of bits that straddle a voxel face (bits are W / B <= 1 voxel wide).
  const TriangleSoup soup = make_torus();
  const GridSpec grid = test::fitted(soup, 64);
  const VoxelGrid uniform = run_slicemap(soup, grid, SlicemapSlicing::kUniform).grid;
  const VoxelGrid local = run_slicemap(soup, grid, SlicemapSlicing::kLocal).grid;
  uint64_t missing = 0, extra = 0;
  for (size_t w = 0; w < uniform.occ.size(); ++w) {
    missing += std::popcount(uniform.occ[w] & ~local.occ[w]);
    extra += std::popcount(local.occ[w] & ~uniform.occ[w]);
  }
  EXPECT_EQ(missing, 0u);
  EXPECT_GT(extra, uniform.voxels_set / 4)
      << "uniform " << uniform.voxels_set << " local " << local.voxels_set;
  RecordProperty("uniform_voxels", std::to_string(uniform.voxels_set));
  RecordProperty("local_extra_voxels", std::to_string(extra));
}

TEST(Slicemap, WholeGridTriangleIsSplitIntoTiles) {
  // One tilted triangle over the whole 200 x 180 footprint: thousands of columns, split into 8 x 8 tiles.
  TriangleSoup soup;
  soup.positions = {{-1, -1, 3.3f, 1}, {410, -1, 20.7f, 1}, {-1, 370, 41.1f, 1}};
  soup.triangles = {{0, 1, 2, 0}};
  const GridSpec grid = test::unit_grid({200, 180, 50});
  for (SlicemapSlicing s : kBoth) {
    VoxelizeStats stats;
    expect_exact(soup, grid, s, "whole grid", VoxelizeOptions{}.record_budget_bytes, &stats);
    EXPECT_EQ(stats.copies, 25u * 23u);  // tiles of the clamped centre range 200 x 180
  }
  expect_uniform_equals_center(soup, grid, "whole grid");
}

TEST(Slicemap, BatchesGiveTheSameSlicemap) {
  const TriangleSoup soup = test::random_soup(24, 300, -1.0f, 1.0f, 0.6f);
  const GridSpec grid = test::fitted(soup, 40);
  for (SlicemapSlicing s : kBoth) {
    VoxelizeStats stats;
    expect_exact(soup, grid, s, "batched", 64 * sizeof(CopyRecord), &stats);
    EXPECT_GT(stats.batches, 3u);
  }
}

TEST(Slicemap, SteepSheetLeavesOneVoxelPerColumn) {
  // The method's failure: a sheet at 80 degrees to the slicing plane crosses ~5.7 voxels per column, but
  // each column gets one fragment, so the slicemap keeps one voxel per column where the surface needs ~6.
  TriangleSoup soup;
  const uint32_t base = 0;
  const float rise = std::tan(glm::radians(80.0f));  // z per unit x
  for (glm::vec3 p : {glm::vec3(0, 0, 2), glm::vec3(5, 0, 2 + 5 * rise), glm::vec3(5, 16, 2 + 5 * rise),
                      glm::vec3(0, 16, 2)})
    soup.positions.push_back(glm::vec4(p, 1.0f));
  soup.triangles = {{base, base + 1, base + 2, 0}, {base, base + 2, base + 3, 0}};
  const GridSpec grid = test::unit_grid({8, 16, 40});
  const VoxelGrid uniform = run_slicemap(soup, grid, SlicemapSlicing::kUniform).grid;
  Voxelizer slice(test::runtime());
  const VoxelGrid conservative = slice.run(soup, grid, VoxelizeOptions{});
  EXPECT_EQ(uniform.voxels_set, 5u * 16u);  // columns i = 0..4 under the sheet, one voxel each
  EXPECT_GT(conservative.voxels_set, 5u * uniform.voxels_set);
}

}  // namespace
}  // namespace voxr
