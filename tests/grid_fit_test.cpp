// fit_grid (core/grid_spec.h) on its own: the fitted grid holds the bounds with the longest axis at the
// requested resolution, keeps every bounding face at least 1/8 voxel from voxel faces and voxel centres (so
// no tie rule decides where a box-shaped mesh ends), centres a cube, honours --dims and exact bounds, and
// refuses what it cannot fit. Then the consequence users see: an axis-aligned cube's solid is symmetric.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "core/grid_spec.h"
#include "test_support.h"
#include "util/error.h"
#include "voxelize/voxelizer.h"

namespace voxr {
namespace {

// Distance of grid coordinate x from the nearest voxel face or centre (multiples of 1/2).
double tie_distance(double x) {
  const double r = x - 0.5 * std::floor(2.0 * x);
  return std::min(r, 0.5 - r);
}

// The bounds' faces in grid units of `g`, low and high, per axis.
void expect_faces_off_ties(const GridSpec& g, const Bounds& b, const std::string& what) {
  for (int a = 0; a < 3; ++a) {
    const double lo = (double(b.lo[a]) - g.origin[a]) / g.voxel_size;
    const double hi = (double(b.hi[a]) - g.origin[a]) / g.voxel_size;
    EXPECT_GE(lo, 0.0) << what << " axis " << a;
    EXPECT_LE(hi, double(g.dims[a])) << what << " axis " << a;
    EXPECT_GE(tie_distance(lo), 0.125 - 1e-4) << what << " axis " << a << " low face at " << lo;
    EXPECT_GE(tie_distance(hi), 0.125 - 1e-4) << what << " axis " << a << " high face at " << hi;
  }
}

TEST(GridFit, FacesKeepOffVoxelFacesAndCentres) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> size(0.001f, 10.0f), corner(-50.0f, 50.0f);
  for (int i = 0; i < 500; ++i) {
    Bounds b;
    b.lo = glm::vec3(corner(rng), corner(rng), corner(rng));
    b.hi = b.lo + glm::vec3(size(rng), size(rng), size(rng));
    if (i % 5 == 0) b.hi.z = b.lo.z + (b.hi.x - b.lo.x) * 0.5f;  // integer and half extents in voxels
    GridRequest r;
    r.resolution = 1 + uint32_t(rng() % 300);
    const GridSpec g = fit_grid(b, r);
    const std::string what = "case " + std::to_string(i) + ", res " + std::to_string(r.resolution);
    const glm::vec3 e = b.size();
    const int longest = e.x >= e.y && e.x >= e.z ? 0 : e.y >= e.z ? 1 : 2;
    EXPECT_EQ(g.dims[longest], r.resolution) << what;
    if (r.resolution >= 4) expect_faces_off_ties(g, b, what);
    if (i % 7 == 0) {  // --dims: the dimensions are kept and the bounds fit inside
      GridRequest d;
      d.dims = glm::uvec3(4 + rng() % 60, 4 + rng() % 60, 4 + rng() % 60);
      const GridSpec gd = fit_grid(b, d);
      EXPECT_EQ(gd.dims, *d.dims) << what;
      expect_faces_off_ties(gd, b, what + " with --dims");
    }
  }
}

TEST(GridFit, CubeIsCentredAQuarterVoxelInside) {
  for (uint32_t res : {2u, 8u, 15u, 16u, 31u, 256u}) {
    const Bounds b{glm::vec3(0.17f, 0.28f, 0.95f), glm::vec3(1.17f, 1.28f, 1.95f)};
    GridRequest r;
    r.resolution = res;
    const GridSpec g = fit_grid(b, r);
    EXPECT_EQ(g.dims, glm::uvec3(res)) << res;
    EXPECT_NEAR(g.voxel_size, 1.0 / (res - 0.5), 1e-6) << res;
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR((b.lo[a] - g.origin[a]) / g.voxel_size, 0.25, 1e-3) << res << " axis " << a;
      EXPECT_NEAR(g.dims[a] - (b.hi[a] - g.origin[a]) / g.voxel_size, 0.25, 1e-3) << res << " axis " << a;
    }
  }
}

TEST(GridFit, ExactBoundsAreWorldAndUsedAsGiven) {
  GridRequest r;
  r.resolution = 10;
  r.bounds = WorldBox(glm::dvec3(1000.5, 2000.0, 3000.0), glm::dvec3(1002.5, 2001.0, 3000.5));
  const glm::dvec3 anchor(1000.0, 2000.0, 3000.0);
  const GridSpec g = fit_grid(Bounds{glm::vec3(0.0f), glm::vec3(1.0f)}, r, anchor);
  EXPECT_EQ(g.anchor, anchor);
  EXPECT_EQ(g.origin, glm::vec3(0.5f, 0.0f, 0.0f));  // relative to the anchor
  EXPECT_FLOAT_EQ(g.voxel_size, 0.2f);
  EXPECT_EQ(g.dims, glm::uvec3(10, 5, 3));
  const glm::dvec3 centre = g.voxel_center_absolute(0, 0, 0);  // float voxel size: 1e-7 relative
  EXPECT_NEAR(centre.x, 1000.6, 1e-5);
  EXPECT_NEAR(centre.y, 2000.1, 1e-5);
  EXPECT_NEAR(centre.z, 3000.1, 1e-5);
}

TEST(GridFit, RefusesWhatItCannotFit) {
  const Bounds unit{glm::vec3(0.0f), glm::vec3(1.0f)};
  auto message = [](const Bounds& b, const GridRequest& r) {
    try {
      fit_grid(b, r);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  GridRequest zero;
  zero.resolution = 0;
  EXPECT_NE(message(unit, zero).find("--res 0 is out of range"), std::string::npos);
  GridRequest huge;
  huge.dims = glm::uvec3(8, 8, kMaxGridDim + 1);
  EXPECT_NE(message(unit, huge).find("out of range"), std::string::npos);
  EXPECT_NE(message(Bounds{}, GridRequest{}).find("bounds are empty"), std::string::npos);
  EXPECT_NE(message(Bounds{glm::vec3(1.0f), glm::vec3(1.0f)}, GridRequest{}).find("single point"),
            std::string::npos);
  GridRequest infinite;
  infinite.bounds = WorldBox(glm::dvec3(0.0), glm::dvec3(INFINITY, 1.0, 1.0));
  EXPECT_NE(message(unit, infinite).find("not finite"), std::string::npos);
}

// Inside and surface sets are mirror images of themselves along every axis.
void expect_symmetric(const VoxelGrid& g, const std::string& what) {
  const glm::uvec3 d = g.spec.dims;
  size_t inside = 0, asymmetric = 0;
  for (uint32_t k = 0; k < d.z; ++k)
    for (uint32_t j = 0; j < d.y; ++j)
      for (uint32_t i = 0; i < d.x; ++i) {
        const uint64_t v = g.spec.linear_index(i, j, k);
        inside += g.is_inside(v);
        for (int axis = 0; axis < 3; ++axis) {
          glm::uvec3 m(i, j, k);
          m[axis] = d[axis] - 1 - m[axis];
          const uint64_t w = g.spec.linear_index(m.x, m.y, m.z);
          asymmetric += g.is_inside(v) != g.is_inside(w) || g.occupied(v) != g.occupied(w);
        }
      }
  EXPECT_GT(inside, 0u) << what;
  EXPECT_EQ(asymmetric, 0u) << what;
}

TEST(GridFit, AxisAlignedCubeSolidIsSymmetric) {
  Voxelizer voxelizer(test::runtime());
  VoxelizeOptions options;
  options.solid = SolidMode::kParity;
  for (uint32_t res : {8u, 15u, 16u, 33u}) {
    for (const glm::vec3 lo : {glm::vec3(0.0f), glm::vec3(0.17f, -3.28f, 10.95f)}) {
      const TriangleSoup cube = test::box_soup(lo, lo + glm::vec3(1.0f));
      const GridSpec grid = test::fitted(cube, res);
      expect_symmetric(voxelizer.run(cube, grid, options), "res " + std::to_string(res));
    }
  }
}

}  // namespace
}  // namespace voxr
