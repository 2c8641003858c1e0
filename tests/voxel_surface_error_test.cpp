// The voxel surface (Chamfer) error: exact values where geometry fixes them.
#include <gtest/gtest.h>

#include <cmath>

#include "core/generators.h"
#include "core/grid_spec.h"
#include "metrics/voxel_surface_error.h"
#include "voxelize/reference_overlap.h"

namespace voxr {
namespace {

GridSpec fitted(const TriangleSoup& soup, uint32_t res) {
  GridRequest request;
  request.resolution = res;
  return fit_grid(soup.bounds(), request, soup.anchor);
}

TEST(VoxelSurfaceError, ConservativeSetHasNoHolesAndThinShell) {
  const TriangleSoup sphere = make_uv_sphere(1.0f, 16, 32);
  const GridSpec spec = fitted(sphere, 32);
  const VoxelGrid exact = reference_overlap(sphere, spec);
  const VoxelSurfaceError e = voxel_surface_error(exact, spec, sphere, 20000);
  // Every surface point lies in a voxel the triangle overlaps.
  EXPECT_EQ(e.mesh_to_voxels, 0.0);
  EXPECT_EQ(e.hole_share, 0.0);
  // A set voxel meets the surface, so its centre lies within half a diagonal of it.
  EXPECT_GT(e.voxels_to_mesh, 0.0);
  EXPECT_LT(e.voxels_to_mesh * 32.0, 0.5 * std::sqrt(3.0));
  EXPECT_EQ(e.voxel_samples, exact.voxels_set);  // fewer set voxels than samples: all of them
}

TEST(VoxelSurfaceError, FallsWithResolution) {
  const TriangleSoup sphere = make_uv_sphere(1.0f, 16, 32);
  double last = 1.0;
  for (uint32_t res : {16u, 32u, 64u}) {
    const GridSpec spec = fitted(sphere, res);
    const double e = voxel_surface_error(reference_overlap(sphere, spec), spec, sphere, 20000).chamfer();
    EXPECT_LT(e, last) << res;
    last = e;
  }
}

TEST(VoxelSurfaceError, EmptyGridIsAllHoles) {
  const TriangleSoup box = make_box();
  const GridSpec spec = fitted(box, 16);
  VoxelGrid empty = reference_overlap(box, spec);
  std::fill(empty.occ.begin(), empty.occ.end(), 0u);
  const VoxelSurfaceError e = voxel_surface_error(empty, spec, box, 5000);
  EXPECT_EQ(e.hole_share, 1.0);
  const double longest = std::max({spec.dims.x, spec.dims.y, spec.dims.z});
  EXPECT_DOUBLE_EQ(e.mesh_to_voxels, kSearchVoxels / longest);
  EXPECT_EQ(e.voxel_samples, 0u);
}

TEST(VoxelSurfaceError, MissingVoxelsAreHoles) {
  const TriangleSoup sphere = make_uv_sphere(1.0f, 16, 32);
  const GridSpec spec = fitted(sphere, 32);
  VoxelGrid thinned = reference_overlap(sphere, spec);
  // Clear every voxel with an even i + j + k: holes in a checkerboard, each a voxel from a set one.
  const glm::uvec3 d = spec.dims;
  for (uint32_t k = 0; k < d.z; ++k)
    for (uint32_t j = 0; j < d.y; ++j)
      for (uint32_t i = 0; i < d.x; ++i)
        if ((i + j + k) % 2 == 0) {
          const uint64_t l = spec.linear_index(i, j, k);
          thinned.occ[l >> 5] &= ~(1u << (l & 31));
        }
  const VoxelSurfaceError e = voxel_surface_error(thinned, spec, sphere, 20000);
  EXPECT_GT(e.mesh_to_voxels, 0.0);
  EXPECT_EQ(e.hole_share, 0.0);  // a cleared voxel's face neighbours are set: no point is half a diagonal off
}

TEST(VoxelSurfaceError, PlaneThroughVoxelCentresIsAtZeroDistance) {
  // A square in the plane y = 0, larger than the grid, whose voxel centres of layer j = 4 lie on it: that
  // layer is the conservative set (the neighbouring layers' boxes end 1/8 voxel before the plane).
  TriangleSoup plane = make_plane(glm::vec2(4.0f), 1);
  GridSpec spec;
  spec.voxel_size = 0.25f;
  spec.dims = glm::uvec3(10, 10, 10);
  spec.origin = glm::vec3(-1.25f, -1.125f, -1.25f);
  spec.anchor = plane.anchor;
  const VoxelGrid exact = reference_overlap(plane, spec);
  const VoxelSurfaceError e = voxel_surface_error(exact, spec, plane, 5000);
  EXPECT_EQ(exact.voxels_set, 100u);
  EXPECT_LE(e.voxels_to_mesh * 10.0, 1e-6);
}

}  // namespace
}  // namespace voxr
