// Host synchronisations: ClRuntime counts every wait for the queue (finish, blocking transfers), not the
// reads that travel with a later wait; a warm frame of the default scene stays within its budget.
#include <gtest/gtest.h>

#include "core/default_scene.h"
#include "render/environment_map.h"
#include "render/frame_renderer.h"
#include "render/render_scene.h"
#include "test_support.h"

namespace voxr {
namespace {

TEST(HostSyncs, FinishAndBlockingTransfersCountDeferredReadsDoNot) {
  ClRuntime& cl = test::runtime();
  cl::Buffer b = cl.buffer(16, "syncs");
  uint32_t values[4] = {1, 2, 3, 4}, back[4] = {};
  const uint64_t before = cl.syncs();
  cl.upload(b, values, 16, "upload syncs");
  EXPECT_EQ(cl.syncs(), before + 1);
  cl.download_later(b, back, 16, "readback syncs");
  EXPECT_EQ(cl.syncs(), before + 1);
  cl.finish();
  EXPECT_EQ(cl.syncs(), before + 2);
  EXPECT_EQ(back[3], 4u);
  cl.download(b, back, 4, "readback syncs");
  EXPECT_EQ(cl.syncs(), before + 3);
}

// The default scene's second frame (the first grows the buffers) with `refraction`.
FrameStats warm_frame(RefractionMethod refraction) {
  Scene scene = default_scene();
  const std::vector<Material> materials = scene.materials;
  const TriangleSoup soup = take_scene_triangles(scene);
  FrameRenderer renderer(test::runtime());
  const CameraFrame camera = make_camera_frame(scene.camera, soup.anchor, soup.bounds(), 96, 72);
  const EnvironmentMap environment = make_environment_map(scene.environment);
  const RenderLight light = render_light(scene.light, environment.mean(), soup.anchor);
  renderer.set_scene(soup, materials);
  renderer.set_environment(environment);  // as the CLI does
  RenderOptions o;
  o.refraction.method = refraction;
  o.refraction.resolution = 64;
  o.shadow_resolution = 64;
  renderer.prepare(o);
  FrameStats stats;
  for (int i = 0; i < 2; ++i) renderer.render(light, camera, o, &stats);
  return stats;
}

// A regression bound, not the requirement: issue 18 asks for at most 3 and a frame makes more today. With
// --refraction none 7: the light grid's voxelization (its four small counts read one at a time and the
// wait at its end), the camera rasterizer's record total, the frame's one last wait (image and samples
// travel with it); the light mesh is kept from the frame before (a static scene). voxel-multi adds the
// refraction grid's voxelization (5). Reading the counts together is what is left.
TEST(HostSyncs, DefaultFrameStaysWithinItsBudget) {
  EXPECT_LE(warm_frame(RefractionMethod::kVoxelMulti).host_syncs, 12u);
  EXPECT_LE(warm_frame(RefractionMethod::kNone).host_syncs, 7u);
}

}  // namespace
}  // namespace voxr
