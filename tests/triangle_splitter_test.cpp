// split_oversized_triangles' quick answer (nothing to split) agrees with its per-triangle rule.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/grid_spec.h"
#include "test_support.h"
#include "voxelize/snapped_triangle.h"
#include "voxelize/triangle_splitter.h"

namespace voxr {
namespace {

// The rule, triangle by triangle: longer than kSplitExtentVoxels on an axis, or (kColumns) wholly more than a
// voxel below or above the grid.
uint64_t triangles_needing_work(const TriangleSoup& soup, const GridSpec& grid, SplitCull cull) {
  const std::array<float, 12> m = grid.world_to_grid();
  uint64_t n = 0;
  for (const glm::uvec4& t : soup.triangles) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (int c = 0; c < 3; ++c) {
      const glm::vec3 g = grid_coords(m, soup.positions[t[c]]);
      lo = glm::min(lo, g);
      hi = glm::max(hi, g);
    }
    const glm::vec3 e = hi - lo;
    const bool far = cull == SplitCull::kColumns && (hi.z < -1.0f || lo.z > float(grid.dims.z) + 1.0f);
    n += std::max({e.x, e.y, e.z}) > kSplitExtentVoxels || far;
  }
  return n;
}

void expect_rule(const TriangleSoup& soup, const GridSpec& grid, uint64_t expected, const std::string& what) {
  for (SplitCull cull : {SplitCull::kGrid, SplitCull::kColumns}) {
    SCOPED_TRACE(what + (cull == SplitCull::kGrid ? ", kGrid" : ", kColumns"));
    uint64_t split = 12345;
    const std::optional<TriangleSoup> pieces = split_oversized_triangles(soup, grid, &split, cull);
    EXPECT_EQ(split, triangles_needing_work(soup, grid, cull));
    EXPECT_EQ(pieces.has_value(), split > 0);
    if (cull == SplitCull::kGrid) {
      EXPECT_EQ(split, expected);
    }
  }
}

// A grid with 1-unit voxels at the origin, so that grid units are world units.
GridSpec unit_grid(glm::uvec3 dims) {
  GridSpec grid;
  grid.dims = dims;
  return grid;
}

TriangleSoup triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  TriangleSoup soup;
  soup.positions = {glm::vec4(a, 1.0f), glm::vec4(b, 1.0f), glm::vec4(c, 1.0f)};
  soup.triangles = {{0, 1, 2, 0}};
  return soup;
}

TEST(TriangleSplitter, NothingToSplitAgreesWithThePerTriangleRule) {
  const TriangleSoup small = test::random_soup(3, 500, -1.0f, 1.0f, 0.2f);
  for (uint32_t res : {16u, 256u, 1999u, 4000u}) {
    GridRequest request;
    request.resolution = res;
    // Small triangles in a grid up to 4000 voxels wide: the soup spans more than kSplitExtentVoxels, no
    // triangle does.
    expect_rule(small, fit_grid(small.bounds(), request), 0, "random soup at " + std::to_string(res));
  }
  // A grid covering only the middle of the soup: in depth, triangles below and above it.
  GridRequest cropped;
  cropped.resolution = 64;
  cropped.bounds = Bounds{glm::vec3(-1.0f, -1.0f, -0.1f), glm::vec3(1.0f, 1.0f, 0.1f)};
  const GridSpec middle = fit_grid({}, cropped);
  expect_rule(small, middle, 0, "random soup, cropped grid");
  EXPECT_GT(triangles_needing_work(small, middle, SplitCull::kColumns), 0u);

  // Exactly kSplitExtentVoxels long is not split; a little longer is.
  const GridSpec grid = unit_grid({4096, 4096, 64});
  expect_rule(triangle({0, 0, 1}, {2000, 0, 1}, {0, 1, 1}), grid, 0, "2000 voxels");
  expect_rule(triangle({0, 0, 1}, {2000.5f, 0, 1}, {0, 1, 1}), grid, 1, "2000.5 voxels");
  // Within a voxel below or above the grid in depth: nothing to flatten; further: kColumns flattens it.
  expect_rule(triangle({0, 0, -1}, {5, 0, -1}, {0, 5, -1}), grid, 0, "one voxel below");
  expect_rule(triangle({0, 0, 65}, {5, 0, 65}, {0, 5, 65}), grid, 0, "one voxel above");
  expect_rule(triangle({0, 0, -1.5f}, {5, 0, -1.5f}, {0, 5, -1.5f}), grid, 0, "1.5 voxels below");
  expect_rule(triangle({0, 0, 66}, {5, 0, 66}, {0, 5, 66}), grid, 0, "two voxels above");

  // Two small triangles 3000 voxels apart, and a vertex no triangle uses far away or NaN.
  TriangleSoup apart = triangle({0, 0, 1}, {1, 0, 1}, {0, 1, 1});
  apart.append(triangle({3000, 0, 1}, {3001, 0, 1}, {3000, 1, 1}));
  expect_rule(apart, grid, 0, "two triangles far apart");
  TriangleSoup unused = triangle({0, 0, 1}, {1, 0, 1}, {0, 1, 1});
  unused.positions.push_back(glm::vec4(1e9f, 0.0f, -1e9f, 1.0f));
  expect_rule(unused, grid, 0, "a far vertex no triangle uses");
  unused.positions.back() = glm::vec4(std::nanf(""), 0.0f, 0.0f, 1.0f);
  expect_rule(unused, grid, 0, "a NaN vertex no triangle uses");
  // A soup not validated yet: a triangle with only NaN corners counts as below the grid for kColumns.
  unused.positions.back().x = 1.0f;
  unused.append(triangle(glm::vec3(std::nanf("")), glm::vec3(std::nanf("")), glm::vec3(std::nanf(""))));
  expect_rule(unused, grid, 0, "a triangle with NaN corners");
  EXPECT_EQ(triangles_needing_work(unused, grid, SplitCull::kColumns), 1u);
}

}  // namespace
}  // namespace voxr
