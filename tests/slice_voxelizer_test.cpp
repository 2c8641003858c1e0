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

// Triangles spanning 9..16 cells per axis, the direct pass's widest (kernels/voxelize/vox_direct.cl: its
// 32-bit edge axes are proven exact up to 16), in both rules, against the reference.
TEST(SliceVoxelizer, DirectPassAtItsWidestSpansEqualsReference) {
  const TriangleSoup soup = test::random_soup(23, 300, -1.0f, 1.0f, 0.45f);
  const GridSpec grid = test::fitted(soup, 64);
  // The soup reaches that range: triangles whose widest cell range is 9..16 (the old limit was 8).
  int wide = 0;
  for (const glm::uvec4& t : soup.triangles) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (uint32_t v : {t.x, t.y, t.z}) {
      const glm::vec3 g = grid.to_grid(glm::vec3(soup.positions[v]));
      lo = glm::min(lo, g);
      hi = glm::max(hi, g);
    }
    const glm::vec3 span = glm::floor(hi) - glm::floor(lo) + 1.0f;
    const float widest = std::max(span.x, std::max(span.y, span.z));
    wide += widest > 8.0f && widest <= 16.0f && span.x * span.y * span.z <= 1024.0f;
  }
  EXPECT_GT(wide, 30);
  for (RasterMode mode : {RasterMode::kConservative, RasterMode::kCenter}) {
    Voxelizer voxelizer(test::runtime());
    VoxelizeOptions options;
    options.mode = mode;
    options.channels = ChannelSet::parse("occ,count,normal,material");
    VoxelizeStats stats;
    const VoxelGrid actual = voxelizer.run(soup, grid, options, &stats);
    EXPECT_GT(stats.direct_triangles, uint64_t(wide));  // those take the direct pass
    EXPECT_EQ(test::compare_grids(reference_voxelize(soup, grid, mode, options.channels), actual), "")
        << raster_mode_name(mode);
  }
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
