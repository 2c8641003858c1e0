// Voxel refraction's grids (render/voxel_refraction.h, RefractionGrid): the fitted fine grid and the coarse
// grid's dimensions and voxel sizes on a known scene (exact), the whole scene's grid with kScene, a path
// that leaves the fine grid's box going on in the coarse level to the opaque object beyond it, and an opaque
// surface coincident with glass winning the voxels they share whatever the materials' order.
#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <vector>

#include "core/generators.h"
#include "core/material.h"
#include "render/camera_frame.h"
#include "render/frame_renderer.h"
#include "render/technique.h"
#include "test_support.h"
#include "voxr_layout.h"

namespace voxr {
namespace {

constexpr uint32_t kGlass = 0, kOpaque = 1;

std::vector<Material> materials() {
  Material glass;
  glass.name = "glass";
  glass.kind = MaterialKind::kDielectric;
  glass.ior = 1.5f;
  Material opaque;
  opaque.name = "opaque";
  opaque.kind = MaterialKind::kOpaque;
  return {glass, opaque};
}

RenderOptions options(RefractionGrid grid, uint32_t res) {
  RenderOptions o;
  o.shadows = ShadowMethod::kNone;
  o.keep_samples = true;
  o.refraction.method = RefractionMethod::kVoxelMulti;
  o.refraction.step = StepRule::kDda;
  o.refraction.grid = grid;
  o.refraction.resolution = res;
  return o;
}

// A camera on the z axis at z = 4 looking down -z; odd size, so the centre pixel's ray is the axis.
CameraFrame camera() {
  CameraFrame f;
  f.eye = glm::vec3(0.0f, 0.5f, 4.0f);
  f.forward = glm::vec3(0.0f, 0.0f, -1.0f);
  f.right = glm::vec3(1.0f, 0.0f, 0.0f);
  f.up = glm::vec3(0.0f, 1.0f, 0.0f);
  f.tan_half_fov_y = std::tan(glm::radians(20.0f));
  f.width = 33;
  f.height = 25;
  f.near_plane = 0.1f;
  f.far_plane = 20.0f;
  return f;
}

RenderLight light() {
  RenderLight l{};
  l.directional = 1;
  l.direction[1] = -1.0f;
  for (int a = 0; a < 3; ++a) l.intensity[a] = l.ambient[a] = 0.5f;
  return l;
}

// A glass block [-0.5, 0.5] x [0, 1] x [-0.25, 0.25] standing on an opaque floor slab [-4, 4] x [-0.05, 0] x
// [-4, 4], and an opaque wall at z in [-3, -2.5] far behind it (outside the fine grid's box).
TriangleSoup scene() {
  TriangleSoup soup;
  soup.append(make_box(glm::vec3(-0.5f, 0.0f, -0.25f), glm::vec3(0.5f, 1.0f, 0.25f)), glm::mat4(1.0f),
              kGlass);
  soup.append(make_box(glm::vec3(-4.0f, -0.05f, -4.0f), glm::vec3(4.0f, 0.0f, 4.0f)), glm::mat4(1.0f),
              kOpaque);
  soup.append(make_box(glm::vec3(-2.0f, -0.05f, -3.0f), glm::vec3(2.0f, 2.0f, -2.5f)), glm::mat4(1.0f),
              kOpaque);
  return soup;
}

TEST(RefractionGrid, FittedLevelsOnAKnownScene) {
  const TriangleSoup soup = scene();
  FrameRenderer renderer(test::runtime());
  renderer.set_scene(soup, materials());
  const RenderOptions fitted = options(RefractionGrid::kFitted, 64);
  renderer.prepare(fitted);
  FrameStats stats;
  renderer.render(light(), camera(), fitted, &stats);
  // Fine: the glass block's longest side (1) over 64 - 2 x 2 margin voxels; x and y 1 / h + 4 = 64 voxels,
  // z 0.5 / h + 4 = 34.
  EXPECT_EQ(stats.refraction_grid.dims, glm::uvec3(64, 64, 34));
  EXPECT_FLOAT_EQ(stats.refraction_grid.voxel_size, 1.0f / 60.0f);
  // Coarse: the whole scene (8 x 2.05 x 8), 64 / 2 = 32 voxels along its longest side with a quarter voxel
  // of margin: h = 8 / 31.5, y 2.05 / h + 0.5 = 8.57 -> 9.
  ASSERT_TRUE(stats.refraction_coarse_grid.has_value());
  EXPECT_EQ(stats.refraction_coarse_grid->dims, glm::uvec3(32, 9, 32));
  EXPECT_FLOAT_EQ(stats.refraction_coarse_grid->voxel_size, 8.0f / 31.5f);
  EXPECT_GT(stats.refraction_coarse_bytes, 0u);
  EXPECT_GT(stats.refraction_bytes, stats.refraction_coarse_bytes);

  // The whole scene's grid alone: 64 along its 8-unit side, h = 8 / 63.5, y 2.05 / h + 0.5 = 16.8 -> 17.
  const RenderOptions whole = options(RefractionGrid::kScene, 64);
  renderer.prepare(whole);
  renderer.render(light(), camera(), whole, &stats);
  EXPECT_EQ(stats.refraction_grid.dims, glm::uvec3(64, 17, 64));
  EXPECT_FLOAT_EQ(stats.refraction_grid.voxel_size, 8.0f / 63.5f);
  EXPECT_FALSE(stats.refraction_coarse_grid.has_value());
}

TEST(RefractionGrid, PathLeavingTheFineBoxMeetsTheWallOnTheCoarseLevel) {
  const TriangleSoup soup = scene();
  FrameRenderer renderer(test::runtime());
  renderer.set_scene(soup, materials());
  const RenderOptions o = options(RefractionGrid::kFitted, 64);
  renderer.prepare(o);
  FrameStats stats;
  const RenderedFrame frame = renderer.render(light(), camera(), o, &stats);
  const CameraFrame cam = camera();
  const size_t centre = size_t(cam.height / 2) * cam.width + cam.width / 2;
  // The axis ray crosses the block's two faces head on and leaves the fine box (z > -0.29) undeviated, to
  // the wall's face at z = -2.5, on the coarse level: the entry of the conservative voxel holding the face,
  // at most two coarse voxels in front of it.
  const RefractionPath& path = frame.paths[centre];
  EXPECT_EQ(path.events & VOXR_PATH_EVENTS_MASK, 2u);
  EXPECT_EQ(path.events & (VOXR_PATH_ENV | VOXR_PATH_LOST | VOXR_PATH_TIR), 0u);
  const SurfaceSample& end = frame.samples[centre];
  EXPECT_EQ(end.triangle, VOXR_VOXEL_HIT);
  EXPECT_EQ(end.material, kOpaque);
  ASSERT_TRUE(stats.refraction_coarse_grid.has_value());
  const float h = stats.refraction_coarse_grid->voxel_size;
  EXPECT_GE(end.position[2], -2.5f - 1e-4f);
  EXPECT_LE(end.position[2], -2.5f + 2.0f * h);
  EXPECT_NEAR(end.position[0], 0.0f, 1e-4f);
}

TEST(RefractionGrid, OpaqueSurfaceCoincidentWithGlassWinsTheSharedVoxels) {
  // The floor listed before the glass: by index alone (the voxelizer's atomic max) the glass would win the
  // voxels where its bottom lies on the floor's top (their normal sums, down and up, cancel), the march
  // would pass them and end on the floor slab's underside, 0.05 down.
  const std::vector<Material> glass_and_floor = materials();
  const std::vector<Material> floor_first = {glass_and_floor[kOpaque], glass_and_floor[kGlass]};
  TriangleSoup soup;
  soup.append(make_box(glm::vec3(-0.5f, 0.0f, -0.5f), glm::vec3(0.5f, 1.0f, 0.5f)), glm::mat4(1.0f), 1u);
  soup.append(make_box(glm::vec3(-2.0f, -0.05f, -2.0f), glm::vec3(2.0f, 0.0f, 2.0f)), glm::mat4(1.0f), 0u);
  FrameRenderer renderer(test::runtime());
  renderer.set_scene(soup, floor_first);
  CameraFrame down = camera();
  down.eye = glm::vec3(0.0f, 3.0f, 0.0f);
  down.forward = glm::vec3(0.0f, -1.0f, 0.0f);
  down.up = glm::vec3(0.0f, 0.0f, -1.0f);
  for (RefractionGrid grid : {RefractionGrid::kFitted, RefractionGrid::kScene}) {
    SCOPED_TRACE(refraction_grid_info(grid).name);
    const RenderOptions o = options(grid, 64);
    renderer.prepare(o);
    FrameStats stats;
    const RenderedFrame frame = renderer.render(light(), down, o, &stats);
    const size_t centre = size_t(down.height / 2) * down.width + down.width / 2;
    // The front surface, then the floor's voxel at the glass's bottom: one event, the path ends on the floor
    // within a voxel of y = 0.
    EXPECT_EQ(frame.paths[centre].events & VOXR_PATH_EVENTS_MASK, 1u);
    EXPECT_EQ(frame.samples[centre].triangle, VOXR_VOXEL_HIT);
    EXPECT_EQ(frame.samples[centre].material, 0u);
    EXPECT_NEAR(frame.samples[centre].position[1], 0.0f, stats.refraction_grid.voxel_size);
  }
}

}  // namespace
}  // namespace voxr
