// The light's grid and mesh built on the device (DeviceLightFrame, kernels/render/shadow/light_project.cl)
// against the host reference (fit_light_frame, project_to_light_grid, split_oversized_triangles): the same
// LightFrame, bit for bit, and the same integer voxels (occ, count, material) when the light mesh is
// voxelized, for directional and point lights, casters reaching behind the near plane and triangles long
// enough to split.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cstring>

#include "core/generators.h"
#include "grid/channel_table.h"
#include "render/light_frame.h"
#include "render/render_scene.h"
#include "test_lights.h"
#include "test_support.h"
#include "voxelize/voxelizer.h"

namespace voxr {
namespace {

// A tree (bark 0, leaves 1) on a floor (2) of `floor_size`.
TriangleSoup tree_on_floor(float floor_size) {
  TriangleSoup soup;
  soup.append(make_plane(glm::vec2(floor_size), 1), glm::mat4(1.0f), 2);
  soup.append(make_tree(0.3f, 7, 1.0f));
  return soup;
}

// A wall from y = -1 to 9 at x = 1 beside a light at (0, 5, 0): part of it lies behind the light's near cut.
TriangleSoup wall_past_the_light() {
  TriangleSoup soup;
  test::add_square(soup, 0.0f, -2.0f, 2.0f, 0);
  const uint32_t b = uint32_t(soup.positions.size());
  soup.positions.push_back({1.0f, -1.0f, -1.0f, 1});
  soup.positions.push_back({1.0f, 9.0f, -1.0f, 1});
  soup.positions.push_back({1.0f, 9.0f, 1.0f, 1});
  soup.positions.push_back({1.0f, -1.0f, 1.0f, 1});
  soup.triangles.push_back({b, b + 1, b + 2, 1});
  soup.triangles.push_back({b, b + 2, b + 3, 1});
  return soup;
}

void expect_same_frame(const LightFrame& host, const LightFrame& device) {
  EXPECT_EQ(std::memcmp(&host.params, &device.params, sizeof(ShadowFrame)), 0)
      << host.describe() << " vs " << device.describe();
  EXPECT_EQ(host.grid.dims, device.grid.dims);
  EXPECT_EQ(host.grid.origin, device.grid.origin);
  EXPECT_EQ(host.grid.voxel_size, device.grid.voxel_size);
  EXPECT_EQ(host.near_depth, device.near_depth);
  EXPECT_EQ(host.far_depth, device.far_depth);
  EXPECT_EQ(host.parallel_point, device.parallel_point);
}

VoxelGrid voxelize(ClRuntime& cl, const DeviceMesh& mesh, const GridSpec& grid, RasterMode mode) {
  VoxelizeOptions o;
  o.method = VoxelizeMethod::kHybrid;
  o.mode = mode;
  o.channels = ChannelSet::parse("occ,count,material");
  Voxelizer v(cl);
  DeviceVoxelGrid out;
  v.run(mesh, grid, o, out);
  return read_back(cl, out);
}

// Fits and builds the light mesh both ways and compares; returns the host mesh's split count.
uint64_t expect_same_as_host(const TriangleSoup& soup, const RenderLight& light, const Bounds& receivers,
                             uint32_t resolution) {
  ClRuntime& cl = test::runtime();
  const LightFrame host = fit_light_frame(light, receivers, soup, resolution);
  const TriangleSoup projected = host.projective() ? project_to_light_grid(soup, host) : TriangleSoup{};
  const DeviceMesh host_mesh =
      upload_mesh(cl, host.projective() ? projected : soup, host.grid, SplitCull::kGrid);

  DeviceMesh scene(cl, soup);
  DeviceLightFrame builder(cl);
  cl.build_programs(builder.programs());
  const LightFrame& device = builder.fit(light, receivers, scene, resolution);
  expect_same_frame(host, device);
  const DeviceMesh& device_mesh = builder.light_mesh(scene);
  EXPECT_EQ(device_mesh.triangle_count(), host_mesh.triangle_count());
  EXPECT_EQ(device_mesh.triangles_split(), host_mesh.triangles_split());
  EXPECT_EQ(device_mesh.bounds().lo, host_mesh.bounds().lo);
  EXPECT_EQ(device_mesh.bounds().hi, host_mesh.bounds().hi);
  for (RasterMode mode : {RasterMode::kCenter, RasterMode::kConservative}) {
    const VoxelGrid h = voxelize(cl, host_mesh, host.grid, mode);
    const VoxelGrid d = voxelize(cl, device_mesh, device.grid, mode);
    EXPECT_GT(h.voxels_set, 0u) << host.describe() << " mode " << int(mode);
    EXPECT_EQ(h.voxels_set, d.voxels_set);
    EXPECT_TRUE(h.occ == d.occ) << "occupancy differs, mode " << int(mode);
    EXPECT_EQ(h.count, d.count);
    EXPECT_EQ(h.material, d.material);
  }
  return host_mesh.triangles_split();
}

// A point light 1e5 units above a floor and a leaf: taken as parallel (an orthographic frame); with a caster
// halfway to the light, a frustum again. The device decides as the host.
TEST(DeviceLightFrame, FarPointLightMatchesTheHost) {
  TriangleSoup soup;
  test::add_square(soup, 0.0f, -3.0f, 3.0f, 0);
  test::add_square(soup, 1.0f, -0.5f, 0.5f, 1);
  const Bounds receivers = soup.bounds();
  const RenderLight light = test::point_light({0.0f, 1e5f, 0.0f});
  expect_same_as_host(soup, light, receivers, 64);
  test::add_square(soup, 5e4f, -0.5f, 0.5f, 1);
  expect_same_as_host(soup, light, receivers, 64);
}

TEST(DeviceLightFrame, TreeUnderAPointLightMatchesTheHost) {
  const TriangleSoup soup = tree_on_floor(6.0f);
  Bounds receivers = soup.bounds();
  receivers.lo += glm::vec3(0.5f, 0.0f, 0.3f);  // a camera's cut of the scene
  expect_same_as_host(soup, test::point_light({3, 7, 2}), receivers, 96);
}

TEST(DeviceLightFrame, TreeUnderADirectionalLightMatchesTheHost) {
  const TriangleSoup soup = tree_on_floor(6.0f);
  expect_same_as_host(soup, test::directional_light({0.3f, -1.0f, 0.2f}), soup.bounds(), 96);
}

TEST(DeviceLightFrame, CasterBehindTheNearCutMatchesTheHost) {
  const TriangleSoup soup = wall_past_the_light();
  Bounds floor;
  floor.extend({-2.0f, 0.0f, -2.0f});
  floor.extend({2.0f, 0.0f, 2.0f});
  expect_same_as_host(soup, test::point_light({0, 5, 0}), floor, 128);
}

TEST(DeviceLightFrame, CastersOutsideTheFootprintDoNotSetTheNearDepth) {
  // A leaf over a floor, and a square high up beside them: it casts (the floor lies beyond its plane) but
  // outside the floor's columns, so the grid starts at the leaf, not at the square.
  TriangleSoup soup;
  test::add_square(soup, 0.0f, -2.0f, 2.0f, 0);
  test::add_square(soup, 1.0f, -0.5f, 0.5f, 1);
  TriangleSoup side;
  test::add_square(side, 3.0f, 6.0f, 7.0f, 1);
  soup.append(side);
  Bounds floor;
  floor.extend({-2.0f, 0.0f, -2.0f});
  floor.extend({2.0f, 0.0f, 2.0f});
  expect_same_as_host(soup, test::point_light({0, 5, 0}), floor, 64);
  const LightFrame f = fit_light_frame(test::point_light({0, 5, 0}), floor, soup, 64);
  EXPECT_GT(f.near_depth, 3.5f);  // the leaf's depth (4) less the margin; the square is at 2
}

TEST(DeviceLightFrame, OversizedTrianglesAreSplitAsOnTheHost) {
  // A floor 4000 wide under receivers 4 wide: its two triangles span far more than 2000 voxels of the grid.
  const TriangleSoup soup = tree_on_floor(4000.0f);
  Bounds receivers;
  receivers.extend({-2.0f, 0.0f, -2.0f});
  receivers.extend({2.0f, 3.0f, 2.0f});
  EXPECT_GT(expect_same_as_host(soup, test::directional_light({0.3f, -1.0f, 0.2f}), receivers, 256), 0u);
  EXPECT_GT(expect_same_as_host(soup, test::point_light({3, 7, 2}), receivers, 256), 0u);
}

}  // namespace
}  // namespace voxr
