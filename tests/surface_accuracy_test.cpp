// The accuracy metrics themselves: conservative voxelization has no errors and no tunnels by definition;
// centre sampling misses voxels and lets rays through steep walls.
#include <gtest/gtest.h>

#include "core/generators.h"
#include "test_support.h"
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

TEST(SurfaceAccuracy, ConservativeIsExactAndWatertight) {
  const TriangleSoup soup = make_torus();
  GridRequest r;
  r.resolution = 64;
  const GridSpec grid = fit_grid(soup.bounds(), r);
  const VoxelGrid exact = voxelize(soup, grid, RasterMode::kConservative);
  const SurfaceAccuracy a = measure_surface_accuracy(exact, exact, soup);
  EXPECT_EQ(a.false_positives + a.false_negatives + a.tunnels, 0u);
  EXPECT_EQ(a.true_positives, exact.voxels_set);
  EXPECT_GT(a.crossings, 1000u);
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
  EXPECT_GT(a.false_negatives, a.exact_voxels / 4);
  // The torus lies in the xz plane: its rim is steep to z, and rays along x and y slip through there.
  EXPECT_GT(a.tunnels, 0u);
  EXPECT_LT(a.tunnels, a.crossings);
  RecordProperty("center_fn", int(a.false_negatives));
  RecordProperty("center_tunnels", int(a.tunnels));
}

}  // namespace
}  // namespace voxr
