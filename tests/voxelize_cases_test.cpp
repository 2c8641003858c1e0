// Every benchmark case (host/bench/voxelize_cases.h) is proven right on a small version before it is timed:
// the same options, on a mesh with small and large triangles, against the CPU references.
#include <gtest/gtest.h>

#include "bench/voxelize_cases.h"
#include "core/generators.h"
#include "test_support.h"
#include "voxelize/reference_inside.h"
#include "voxelize/reference_voxelizer.h"
#include "voxelize/sparse_voxelizer.h"

namespace voxr {
namespace {

TEST(VoxelizeCases, EveryCaseEqualsTheReference) {
  TriangleSoup soup = make_torus();
  soup.append(make_uv_sphere(0.3f, 12, 24), glm::mat4(1.0f), 2);
  GridRequest request;
  request.resolution = 40;
  const GridSpec grid = fit_grid(soup.bounds(), request);
  Voxelizer voxelizer(test::runtime());
  SparseVoxelizer sparse(test::runtime());
  ASSERT_GE(voxelize_cases().size(), 5u);
  for (const VoxelizeCase& c : voxelize_cases()) {
    const VoxelizeOptions options = c.options();
    const VoxelGrid actual =
        c.layout == "sparse" ? to_dense(sparse.run(soup, grid, options)) : voxelizer.run(soup, grid, options);
    EXPECT_EQ(test::compare_grids(reference_voxelize(soup, grid, options.mode, options.channels), actual), "")
        << c.name;
    if (options.solid) {
      const ReferenceSolid ref = reference_solid(soup, grid, *options.solid);
      EXPECT_EQ(compare_bits(actual.inside, ref.inside).total(), 0u) << c.name;
    }
  }
  EXPECT_THROW(find_voxelize_case("nope"), Error);
}

}  // namespace
}  // namespace voxr
