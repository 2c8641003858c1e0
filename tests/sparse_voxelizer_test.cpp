// The sparse (brick) voxelizer against the dense one: the same voxels and channel values, bit for bit, on
// every slice-family method and rule, on meshes with small and large triangles, thin walls and a floor, in
// one slab and in many (a small memory budget), and the brick layout's own invariants.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>

#include <fmt/format.h>

#include "core/generators.h"
#include "core/mesh_loader.h"
#include "grid/sparse_voxel_grid.h"
#include "test_support.h"
#include "voxelize/sparse_voxelizer.h"
#include "voxelize/voxelizer.h"

namespace voxr {
namespace {

// Every field of two sparse grids, exactly (normals too: the same kernels' floats).
std::string compare_sparse(const SparseVoxelGrid& expected, const SparseVoxelGrid& actual) {
  if (expected.brick_dims != actual.brick_dims) return "brick dims differ";
  if (expected.brick_index != actual.brick_index)
    return fmt::format("bricks differ: {} expected, {} actual", expected.bricks(), actual.bricks());
  if (expected.brick_bits != actual.brick_bits) return "brick bits differ";
  if (expected.brick_rank != actual.brick_rank) return "brick ranks differ";
  if (expected.voxels_set != actual.voxels_set) return "voxels_set differs";
  if (expected.count != actual.count) return "count differs";
  if (expected.material != actual.material) return "material differs";
  if (expected.color != actual.color) return "color differs";
  if (expected.normal_sum.size() != actual.normal_sum.size()) return "normal sums differ in size";
  for (size_t i = 0; i < expected.normal_sum.size(); ++i)
    if (expected.normal_sum[i] != actual.normal_sum[i]) return fmt::format("normal sum {} differs", i);
  if (expected.normal.size() != actual.normal.size()) return "normals differ in size";
  for (size_t i = 0; i < expected.normal.size(); ++i)
    if (std::memcmp(&expected.normal[i], &actual.normal[i], sizeof(glm::vec3)) != 0)
      return fmt::format("normal {} differs", i);
  return "";
}

void expect_sparse_equals_dense(const TriangleSoup& soup, const GridSpec& grid,
                                const VoxelizeOptions& options, uint64_t budget, const std::string& what,
                                uint64_t min_slabs = 1) {
  Voxelizer dense(test::runtime());
  const VoxelGrid expected = dense.run(soup, grid, options);
  ASSERT_GT(expected.voxels_set, 0u) << what;
  SparseVoxelizer sparse(test::runtime());
  SparseStats stats;
  const SparseVoxelGrid actual = sparse.run(soup, grid, options, budget, nullptr, &stats);
  EXPECT_EQ(compare_sparse(to_sparse(expected), actual), "")
      << what << " " << method_info(options.method).name << " " << raster_mode_name(options.mode) << " "
      << options.channels.to_string() << " budget " << budget;
  EXPECT_GE(stats.slabs, min_slabs) << what;
  EXPECT_GE(stats.bricks_marked, stats.bricks_kept) << what;
  EXPECT_EQ(stats.bricks_kept, actual.bricks()) << what;
}

// A budget that allows `layers` brick layers of `grid` per slab.
uint64_t budget_for_layers(const GridSpec& grid, uint64_t layers) {
  const glm::uvec3 b = brick_dims_of(grid.dims);
  const uint64_t layer = uint64_t(b.x) * b.y;
  return 4 * layers * (layer / 8 + layer / 4 + 16);
}

TEST(SparseVoxelizer, EveryMethodAndRuleEqualsDense) {
  // Small triangles (direct pass), large ones (slice path) and a floor reaching the grid's edges.
  TriangleSoup soup = make_torus();
  test::add_square(soup, -0.6f, -1.6f, 1.6f, 2);
  const GridSpec grid = test::fitted(soup, 90);
  for (VoxelizeMethod method : {VoxelizeMethod::kHybrid, VoxelizeMethod::kSlice, VoxelizeMethod::kGrid})
    for (RasterMode mode : {RasterMode::kConservative, RasterMode::kCenter})
      for (const char* channels : {"occ", "occ,count,normal,material"}) {
        VoxelizeOptions options;
        options.method = method;
        options.mode = mode;
        options.channels = ChannelSet::parse(channels);
        // one slab, and slabs of one brick layer
        expect_sparse_equals_dense(soup, grid, options, 0, "torus+floor");
        expect_sparse_equals_dense(soup, grid, options, budget_for_layers(grid, 1), "torus+floor, 1 layer",
                                   brick_dims_of(grid.dims).z);
      }
}

TEST(SparseVoxelizer, ThinWallsSubVoxelTrianglesAndOddDims) {
  VoxelizeOptions options;
  options.channels = ChannelSet::parse("occ,count,normal,material");
  // A thin box (two coincident-ish walls 1/10 voxel apart) on a grid whose dims are not multiples of 8.
  const TriangleSoup wall = test::box_soup({0.1f, 0.1f, 0.1f}, {0.9f, 0.9f, 0.1013f}, 1);
  const GridSpec wall_grid = test::unit_grid({77, 45, 29});
  expect_sparse_equals_dense(wall, wall_grid, options, 0, "thin wall");
  expect_sparse_equals_dense(wall, wall_grid, options, budget_for_layers(wall_grid, 2),
                             "thin wall, 2 layers");
  const TriangleSoup dust = test::random_soup(7, 400, -1.0f, 1.0f, 0.01f);
  expect_sparse_equals_dense(dust, test::fitted(dust, 100), options,
                             budget_for_layers(test::fitted(dust, 100), 3), "sub-voxel triangles");
}

TEST(SparseVoxelizer, BunnyEqualsDense) {
  const std::string path = test::mesh_path("bunny.obj");
  if (path.empty()) GTEST_SKIP() << "bunny.obj missing: run scripts/fetch-meshes.sh";
  const TriangleSoup soup = load_mesh(path);
  VoxelizeOptions options;
  options.channels = ChannelSet::parse("occ,count,normal,material");
  const GridSpec grid = test::fitted(soup, 200);
  expect_sparse_equals_dense(soup, grid, options, budget_for_layers(grid, 4), "bunny", 7);
}

TEST(SparseVoxelizer, ColourEqualsDense) {
  // Vertex colours from positions on a torus over a floor, in slabs of one brick layer.
  TriangleSoup soup = make_torus();
  test::add_square(soup, -0.6f, -1.6f, 1.6f, 2);
  soup.colors.vertex_rgba.resize(soup.positions.size());
  for (size_t v = 0; v < soup.positions.size(); ++v) {
    const glm::vec4 p = soup.positions[v];
    soup.colors.vertex_rgba[v] = uint32_t(int(p.x * 80.0f) & 255) | uint32_t(int(p.y * 80.0f) & 255) << 8 |
                                 uint32_t(int(p.z * 80.0f) & 255) << 16 | 0xff000000u;
  }
  const GridSpec grid = test::fitted(soup, 70);
  VoxelizeOptions options;
  options.channels = ChannelSet::parse("occ,count,color");
  expect_sparse_equals_dense(soup, grid, options, budget_for_layers(grid, 1), "coloured torus+floor",
                             brick_dims_of(grid.dims).z);
}

TEST(SparseVoxelizer, RefusesWhatNeedsDenseGrids) {
  VoxelizeOptions solid;
  solid.solid = SolidMode::kParity;
  solid.channels.add(Channel::kInside);
  EXPECT_THROW(SparseVoxelizer::validate(solid), Error);
  VoxelizeOptions slicemap;
  slicemap.method = VoxelizeMethod::kSlicemap;
  EXPECT_THROW(SparseVoxelizer::validate(slicemap), Error);
  VoxelizeOptions lists;
  lists.channels = ChannelSet::parse("occ,count");
  lists.triangle_lists = true;
  EXPECT_THROW(SparseVoxelizer::validate(lists), Error);
}

TEST(SparseVoxelGrid, ToSparseAndBackIsTheIdentity) {
  const TriangleSoup soup = make_torus();
  Voxelizer voxelizer(test::runtime());
  VoxelizeOptions options;
  options.channels = ChannelSet::parse("occ,count,normal,material");
  const VoxelGrid dense = voxelizer.run(soup, test::fitted(soup, 61), options);
  const SparseVoxelGrid sparse = to_sparse(dense);
  EXPECT_EQ(test::compare_grids(dense, to_dense(sparse)), "");
  // Bricks ascend, hold a voxel each, and their ranks add up.
  ASSERT_EQ(sparse.brick_rank.size(), sparse.bricks() + 1);
  for (size_t b = 0; b < sparse.bricks(); ++b) {
    if (b > 0) {
      EXPECT_LT(sparse.brick_index[b - 1], sparse.brick_index[b]);
    }
    uint64_t set = 0;
    for (uint32_t w = 0; w < kBrickWords; ++w) set += std::popcount(sparse.brick_bits[b * kBrickWords + w]);
    EXPECT_GT(set, 0u);
    EXPECT_EQ(sparse.brick_rank[b + 1] - sparse.brick_rank[b], set);
  }
  // occupied() agrees with the dense bits everywhere.
  const glm::uvec3 d = dense.spec.dims;
  for (uint32_t k = 0; k < d.z; ++k)
    for (uint32_t j = 0; j < d.y; ++j)
      for (uint32_t i = 0; i < d.x; ++i) ASSERT_EQ(sparse.occupied(i, j, k), dense.occupied(i, j, k));
}

}  // namespace
}  // namespace voxr
