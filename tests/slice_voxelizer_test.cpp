// The slice voxelizer's kernels against the exact CPU reference: same snapped input, integer channels
// compared exactly, unit normals within 1e-5.
#include <gtest/gtest.h>

#include "test_support.h"
#include "voxelize/reference_voxelizer.h"
#include "voxelize/voxelizer.h"

namespace voxr {
namespace {

ChannelSet all_channels() {
  return ChannelSet::parse("occ,count,normal,material");
}

void expect_matches_reference(const TriangleSoup& soup, const GridSpec& grid, RasterMode mode,
                              uint32_t rows_per_copy = 4) {
  Voxelizer voxelizer(test::runtime());
  VoxelizeOptions options;
  options.mode = mode;
  options.channels = all_channels();
  options.rows_per_copy = rows_per_copy;
  const VoxelGrid actual = voxelizer.run(soup, grid, options);
  const VoxelGrid expected = reference_voxelize(soup, grid, mode, options.channels);
  EXPECT_GT(expected.voxels_set, 0u);
  EXPECT_EQ(test::compare_grids(expected, actual), "") << raster_mode_name(mode);
}

TEST(SliceVoxelizer, RandomSoupConservativeEqualsReference) {
  const TriangleSoup soup = test::random_soup(1, 400, -1.0f, 1.0f, 0.3f);
  expect_matches_reference(soup, test::fitted(soup, 48), RasterMode::kConservative);
}

TEST(SliceVoxelizer, RandomSoupCenterEqualsReference) {
  const TriangleSoup soup = test::random_soup(2, 400, -1.0f, 1.0f, 0.3f);
  expect_matches_reference(soup, test::fitted(soup, 48), RasterMode::kCenter);
}

TEST(SliceVoxelizer, LargeTrianglesUseClippingAndStayExact) {
  const TriangleSoup soup = test::random_soup(3, 60, -1.0f, 1.0f, 2.0f);
  for (RasterMode mode : {RasterMode::kConservative, RasterMode::kCenter})
    expect_matches_reference(soup, test::fitted(soup, 40), mode);
}

TEST(SliceVoxelizer, BoxOnVoxelFacesAtSeveralResolutions) {
  // Faces exactly on voxel boundaries: the closed-box rule marks both neighbours.
  const TriangleSoup soup = test::box_soup({-1, -1, -1}, {1, 1, 1});
  for (uint32_t n : {8u, 16u, 33u}) {
    GridRequest r;
    r.bounds = Bounds{{-2, -2, -2}, {2, 2, 2}};
    r.resolution = n;
    for (RasterMode mode : {RasterMode::kConservative, RasterMode::kCenter})
      expect_matches_reference(soup, fit_grid({}, r), mode);
  }
}

TEST(SliceVoxelizer, RowsPerCopyDoesNotChangeTheResult) {
  const TriangleSoup soup = test::random_soup(4, 200, -1.0f, 1.0f, 1.0f);
  for (uint32_t rows : {1u, 3u, 16u})
    expect_matches_reference(soup, test::fitted(soup, 32), RasterMode::kConservative, rows);
}

TEST(SliceVoxelizer, BatchesGiveTheSameGrid) {
  const TriangleSoup soup = test::random_soup(5, 300, -1.0f, 1.0f, 0.5f);
  const GridSpec grid = test::fitted(soup, 40);
  Voxelizer voxelizer(test::runtime());
  VoxelizeOptions one;
  one.channels = all_channels();
  VoxelizeOptions many = one;
  many.record_budget_bytes = 64 * sizeof(CopyRecord);
  VoxelizeStats stats;
  const VoxelGrid a = voxelizer.run(soup, grid, one);
  const VoxelGrid b = voxelizer.run(soup, grid, many, &stats);
  EXPECT_GT(stats.batches, 3u);
  EXPECT_EQ(test::compare_grids(a, b, 0.0f), "");
}

}  // namespace
}  // namespace voxr

namespace voxr {
namespace {

TEST(SliceVoxelizer, GridBaselineEqualsSliceMethod) {
  // Llamas' per-slab passes and the papers' duplication share the scanline code: identical voxels.
  const TriangleSoup soup = test::random_soup(6, 300, -1.0f, 1.0f, 0.8f);
  const GridSpec grid = test::fitted(soup, 40);
  Voxelizer voxelizer(test::runtime());
  for (RasterMode mode : {RasterMode::kConservative, RasterMode::kCenter}) {
    VoxelizeOptions slice;
    slice.mode = mode;
    slice.channels = all_channels();
    VoxelizeOptions per_slab = slice;
    per_slab.method = VoxelizeMethod::kGrid;
    VoxelizeStats stats;
    const VoxelGrid a = voxelizer.run(soup, grid, slice);
    const VoxelGrid b = voxelizer.run(soup, grid, per_slab, &stats);
    EXPECT_EQ(stats.work_items, soup.triangle_count() * grid.dims.z);
    EXPECT_EQ(test::compare_grids(a, b, 0.0f), "") << raster_mode_name(mode);
    EXPECT_EQ(test::compare_grids(reference_voxelize(soup, grid, mode, slice.channels), b), "");
  }
}

}  // namespace
}  // namespace voxr
