// The accuracy metrics themselves, each count checked against one computed here another way: a hand-built
// pair with known extra and missing voxels, conservative voxelization against the exact overlap set (no
// misses, no tunnels), and centre sampling, which misses voxels and lets rays through steep walls.
#include <gtest/gtest.h>

#include <cstdint>
#include <set>

#include "core/generators.h"
#include "test_support.h"
#include "voxelize/reference_overlap.h"
#include "voxelize/surface_accuracy.h"
#include "voxelize/voxelizer.h"

namespace voxr {
namespace {

VoxelGrid voxelize(const TriangleSoup& soup, const GridSpec& grid, RasterMode mode) {
  Voxelizer voxelizer(test::runtime());
  VoxelizeOptions options;
  options.mode = mode;
  return voxelizer.run(soup, grid, options);
}

// Voxels of `a` not set in `b`, one voxel at a time through the (i, j, k) accessor (not the word loop of
// measure_surface_accuracy).
uint64_t count_set_not_in(const VoxelGrid& a, const VoxelGrid& b) {
  uint64_t n = 0;
  const glm::uvec3 d = a.spec.dims;
  for (uint32_t k = 0; k < d.z; ++k)
    for (uint32_t j = 0; j < d.y; ++j)
      for (uint32_t i = 0; i < d.x; ++i) n += a.occupied(i, j, k) && !b.occupied(i, j, k);
  return n;
}

VoxelGrid grid_with(const GridSpec& spec, const std::set<uint64_t>& voxels) {
  VoxelGrid g;
  g.spec = spec;
  g.occ.assign(size_t((spec.voxel_count() + 31) / 32), 0u);
  for (uint64_t v : voxels) g.occ[v / 32] |= 1u << (v % 32);
  g.voxels_set = voxels.size();
  return g;
}

TEST(SurfaceAccuracy, CountsHandBuiltExtraAndMissingVoxels) {
  // 7x5x3 = 105 voxels: four occupancy words, the last one partial (bits 105..127 stay clear).
  const GridSpec spec = test::unit_grid({7, 5, 3});
  const std::set<uint64_t> exact_set = {0, 1, 2, 31, 32, 33, 40, 63, 64, 70, 95, 96, 100, 104};
  std::set<uint64_t> result_set = exact_set;
  for (uint64_t missing : {1, 32, 63, 104}) result_set.erase(missing);   // 4 false negatives
  for (uint64_t extra : {3, 30, 65, 97, 103}) result_set.insert(extra);  // 5 false positives
  const VoxelGrid exact = grid_with(spec, exact_set);
  const VoxelGrid result = grid_with(spec, result_set);
  const SurfaceAccuracy a = measure_surface_accuracy(result, exact, TriangleSoup{});
  EXPECT_EQ(a.exact_voxels, 14u);
  EXPECT_EQ(a.true_positives, 10u);
  EXPECT_EQ(a.false_positives, 5u);
  EXPECT_EQ(a.false_negatives, 4u);
  EXPECT_EQ(a.crossings, 0u);  // no triangles
  EXPECT_EQ(a.tunnels, 0u);
  // Swapping the roles swaps the errors.
  const SurfaceAccuracy b = measure_surface_accuracy(exact, result, TriangleSoup{});
  EXPECT_EQ(b.false_positives, 4u);
  EXPECT_EQ(b.false_negatives, 5u);
  EXPECT_EQ(b.true_positives, 10u);
  EXPECT_EQ(b.exact_voxels, 15u);
}

TEST(SurfaceAccuracy, ConservativeContainsTheExactSetAndIsWatertight) {
  const TriangleSoup soup = make_torus();
  GridRequest r;
  r.resolution = 64;
  const GridSpec grid = fit_grid(soup.bounds(), r);
  const VoxelGrid exact = reference_overlap(soup, grid);
  const VoxelGrid conservative = voxelize(soup, grid, RasterMode::kConservative);
  const SurfaceAccuracy a = measure_surface_accuracy(conservative, exact, soup);
  EXPECT_EQ(a.exact_voxels, exact.voxels_set);
  EXPECT_EQ(a.false_negatives, 0u);
  EXPECT_EQ(a.true_positives, exact.voxels_set);
  // Extra voxels are those within the snap widening; counted here voxel by voxel.
  EXPECT_EQ(a.false_positives, count_set_not_in(conservative, exact));
  EXPECT_EQ(a.true_positives + a.false_positives, conservative.voxels_set);
  EXPECT_EQ(a.tunnels, 0u);
  EXPECT_GT(a.crossings, 1000u);
}

// Conservative measured against centre sampling as if centre were exact: the conservative voxels centre
// sampling misses are all false positives (many), and none is a false negative (centre is a subset).
TEST(SurfaceAccuracy, ConservativeAgainstCenterCountsExtraVoxelsAsFalsePositives) {
  const TriangleSoup soup = make_torus();
  const GridSpec grid = test::fitted(soup, 48);
  const VoxelGrid conservative = voxelize(soup, grid, RasterMode::kConservative);
  const VoxelGrid center = voxelize(soup, grid, RasterMode::kCenter);
  const uint64_t extra = count_set_not_in(conservative, center);
  ASSERT_GT(extra, center.voxels_set / 4);
  ASSERT_EQ(count_set_not_in(center, conservative), 0u);
  const SurfaceAccuracy a = measure_surface_accuracy(conservative, center, soup);
  EXPECT_EQ(a.false_positives, extra);
  EXPECT_EQ(a.false_negatives, 0u);
  EXPECT_EQ(a.true_positives, center.voxels_set);
  EXPECT_EQ(a.exact_voxels, center.voxels_set);
  EXPECT_EQ(a.tunnels, 0u);  // the conservative set closes every crossing
}

TEST(SurfaceAccuracy, CenterModeMissesVoxelsAndLeaksThroughSteepWalls) {
  const TriangleSoup soup = make_torus();
  GridRequest r;
  r.resolution = 64;
  const GridSpec grid = fit_grid(soup.bounds(), r);
  const VoxelGrid exact = voxelize(soup, grid, RasterMode::kConservative);
  const VoxelGrid center = voxelize(soup, grid, RasterMode::kCenter);
  const SurfaceAccuracy a = measure_surface_accuracy(center, exact, soup);
  EXPECT_EQ(a.false_positives, 0u);  // centre voxels are a subset of the touched ones
  EXPECT_EQ(a.false_negatives, count_set_not_in(exact, center));
  EXPECT_GT(a.false_negatives, a.exact_voxels / 4);
  // The torus lies in the xz plane: its rim is steep to z, and rays along x and y slip through there.
  EXPECT_GT(a.tunnels, 0u);
  EXPECT_LT(a.tunnels, a.crossings);
  RecordProperty("center_fn", int(a.false_negatives));
  RecordProperty("center_tunnels", int(a.tunnels));
}

}  // namespace
}  // namespace voxr
