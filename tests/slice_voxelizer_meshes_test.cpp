// The slice voxelizer on the procedural and Debian-packaged meshes and on the edge cases that break
// voxelizers: everything compared exactly with the CPU reference.
#include <gtest/gtest.h>

#include "core/generators.h"
#include "core/mesh_loader.h"
#include "test_support.h"
#include "voxelize/reference_voxelizer.h"
#include "voxelize/voxelizer.h"

namespace voxr {
namespace {

const ChannelSet kAll = ChannelSet::parse("occ,count,normal,material");

VoxelGrid run_kernels(const TriangleSoup& soup, const GridSpec& grid, RasterMode mode) {
  Voxelizer voxelizer(test::runtime());
  VoxelizeOptions options;
  options.mode = mode;
  options.channels = kAll;
  return voxelizer.run(soup, grid, options);
}

void expect_exact(const TriangleSoup& soup, const GridSpec& grid, RasterMode mode, const std::string& what) {
  const VoxelGrid actual = run_kernels(soup, grid, mode);
  const VoxelGrid expected = reference_voxelize(soup, grid, mode, kAll);
  EXPECT_GT(expected.voxels_set, 0u) << what;
  EXPECT_EQ(test::compare_grids(expected, actual), "") << what << " " << raster_mode_name(mode);
}

TEST(SliceVoxelizerMeshes, ProceduralMeshesEqualReference) {
  const std::pair<const char*, TriangleSoup> meshes[] = {
      {"torus", make_torus()},
      {"sphere", make_uv_sphere(1.0f, 16, 32)},
      {"vase", make_vase()},
      {"tree", make_tree(1.0f, 7)},
  };
  for (const auto& [name, soup] : meshes)
    for (RasterMode mode : {RasterMode::kConservative, RasterMode::kCenter})
      expect_exact(soup, test::fitted(soup, 64), mode, name);
}

TEST(SliceVoxelizerMeshes, DebianMeshesEqualReference) {
  for (const char* name : {"bunny.obj", "armadillo.off"}) {
    const std::string path = test::mesh_path(name);
    if (path.empty()) GTEST_SKIP() << name << " missing: run scripts/fetch-meshes.sh";
    const TriangleSoup soup = load_mesh(path);
    expect_exact(soup, test::fitted(soup, 96), RasterMode::kConservative, name);
    expect_exact(soup, test::fitted(soup, 96), RasterMode::kCenter, name);
  }
}

TEST(SliceVoxelizerMeshes, SubVoxelTriangles) {
  const TriangleSoup soup = test::random_soup(11, 500, -1.0f, 1.0f, 0.004f);
  for (RasterMode mode : {RasterMode::kConservative, RasterMode::kCenter})
    expect_exact(soup, test::fitted(soup, 64), mode, "sub-voxel");
}

TEST(SliceVoxelizerMeshes, TriangleSpanningTheWholeGrid) {
  TriangleSoup soup;
  soup.positions = {{-1, -1, -1, 1}, {1, -0.8f, 0.9f, 1}, {0.2f, 1, 1, 1}};
  soup.triangles = {{0, 1, 2, 3}};
  for (RasterMode mode : {RasterMode::kConservative, RasterMode::kCenter})
    expect_exact(soup, test::fitted(soup, 70), mode, "spanning");
}

TEST(SliceVoxelizerMeshes, MeshTouchingTheGridBounds) {
  // Exact bounds equal to the box: its faces lie on the grid's outer faces.
  const TriangleSoup soup = test::box_soup({0, 0, 0}, {1, 1, 1});
  GridRequest r;
  r.bounds = Bounds{{0, 0, 0}, {1, 1, 1}};
  r.resolution = 20;
  for (RasterMode mode : {RasterMode::kConservative, RasterMode::kCenter})
    expect_exact(soup, fit_grid({}, r), mode, "touching bounds");
}

TEST(SliceVoxelizerMeshes, DegenerateTrianglesAreTheirSegmentOrPoint) {
  // Documented behaviour: conservative mode voxelizes a zero-area triangle as the segment or point it is;
  // centre mode sets nothing for it (no projected area). Normal sums get zero from it.
  TriangleSoup soup;
  soup.positions = {{0, 0, 0, 1}, {1, 1, 1, 1}, {0.5f, 0.5f, 0.5f, 1}, {0.3f, 0.7f, 0.2f, 1}, {1, 0, 0, 1}};
  soup.triangles = {{0, 1, 2, 0}, {3, 3, 3, 1}, {0, 4, 1, 2}};
  GridRequest r;
  r.bounds = Bounds{{-0.1f, -0.1f, -0.1f}, {1.1f, 1.1f, 1.1f}};
  r.resolution = 24;
  const GridSpec grid = fit_grid({}, r);
  expect_exact(soup, grid, RasterMode::kConservative, "degenerate");
  TriangleSoup only_degenerate = soup;
  only_degenerate.triangles.pop_back();
  EXPECT_EQ(run_kernels(only_degenerate, grid, RasterMode::kCenter).voxels_set, 0u);
  const VoxelGrid segment = run_kernels(only_degenerate, grid, RasterMode::kConservative);
  EXPECT_GE(segment.voxels_set, 24u);  // the diagonal segment crosses at least one voxel per slab
}

TEST(SliceVoxelizerMeshes, OversizedTrianglesAreSplitAndStayClose) {
  // A ground plane far larger than the grid: split on the host, then exact against the reference that
  // sees the same pieces; the result equals the unsplit plane's voxels inside the grid.
  TriangleSoup soup;
  soup.positions = {{-5000, 0.25f, -5000, 1}, {5000, 0.25f, -5000, 1}, {0, 0.25f, 5000, 1}};
  soup.triangles = {{0, 1, 2, 0}};
  GridRequest r;
  r.bounds = Bounds{{0, 0, 0}, {1, 1, 1}};
  r.resolution = 16;
  const GridSpec grid = fit_grid({}, r);
  Voxelizer voxelizer(test::runtime());
  VoxelizeOptions options;
  VoxelizeStats stats;
  const VoxelGrid g = voxelizer.run(soup, grid, options, &stats);
  EXPECT_EQ(stats.triangles_split, 1u);
  // y = 0.25 is exactly the boundary between layers 3 and 4 of 16: both layers, every column.
  EXPECT_EQ(g.voxels_set, 2u * 16 * 16);
  for (uint32_t k = 0; k < 16; ++k)
    for (uint32_t i = 0; i < 16; ++i) {
      EXPECT_TRUE(g.occupied(i, 3, k));
      EXPECT_TRUE(g.occupied(i, 4, k));
    }
}

TEST(SliceVoxelizerMeshes, RepeatedRunsAreBitIdentical) {
  const TriangleSoup soup = make_tree(2.0f, 3);
  const GridSpec grid = test::fitted(soup, 80);
  const VoxelGrid a = run_kernels(soup, grid, RasterMode::kConservative);
  const VoxelGrid b = run_kernels(soup, grid, RasterMode::kConservative);
  EXPECT_EQ(a.occ, b.occ);
  EXPECT_EQ(a.count, b.count);
  EXPECT_EQ(a.normal_sum, b.normal_sum);
  EXPECT_EQ(a.material, b.material);
  for (size_t r = 0; r < a.normal.size(); ++r) ASSERT_EQ(a.normal[r], b.normal[r]);
}

// Rays along x through voxel-centre (y, z) lines that cross the wall but meet no set voxel: the papers'
// holes at steep triangles.
uint64_t wall_holes(const VoxelGrid& g, float slope, float offset) {
  uint64_t holes = 0;
  for (uint32_t k = 0; k < g.spec.dims.z; ++k)
    for (uint32_t j = 0; j < g.spec.dims.y; ++j) {
      const glm::vec3 c = g.spec.voxel_center_world(0, j, k);
      const float x = slope * c.z + offset;  // the wall: x = slope * z + offset
      const float gx = (x - g.spec.origin.x) / g.spec.voxel_size;
      if (gx < 0.0f || gx >= float(g.spec.dims.x)) continue;
      bool hit = false;
      for (uint32_t i = 0; i < g.spec.dims.x && !hit; ++i) hit = g.occupied(i, j, k);
      holes += !hit;
    }
  return holes;
}

TEST(SliceVoxelizerMeshes, CenterModeLeavesHolesInSteepWallsConservativeDoesNot) {
  const float slope = 0.2f, offset = 0.4f;  // nearly parallel to the slicing axis z
  TriangleSoup wall;
  wall.positions = {{slope * -1 + offset, -1, -1, 1},
                    {slope * -1 + offset, 1, -1, 1},
                    {slope * 1 + offset, 1, 1, 1},
                    {slope * 1 + offset, -1, 1, 1}};
  wall.triangles = {{0, 1, 2, 0}, {0, 2, 3, 0}};
  GridRequest r;
  r.bounds = Bounds{{-1, -1, -1}, {1, 1, 1}};
  r.resolution = 64;
  const GridSpec grid = fit_grid({}, r);
  const uint64_t center_holes = wall_holes(run_kernels(wall, grid, RasterMode::kCenter), slope, offset);
  const uint64_t conservative_holes =
      wall_holes(run_kernels(wall, grid, RasterMode::kConservative), slope, offset);
  // Centre sampling covers one column in 1/slope = 5 along x for this wall: most rows have a hole.
  EXPECT_GT(center_holes, 64u * 64u / 2);
  EXPECT_EQ(conservative_holes, 0u);
  RecordProperty("center_holes", int(center_holes));
}

}  // namespace
}  // namespace voxr
