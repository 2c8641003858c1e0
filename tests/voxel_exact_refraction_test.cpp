// `--refraction voxel-exact` (render/techniques/voxel_exact_refraction.cpp) against the matched reference
// (eval/reference_comparison.h): the same path model on the same triangles, so the image agrees to float
// level and the event sequences nearly everywhere, at any grid resolution.
#include <gtest/gtest.h>

#include <cmath>
#include <span>

#include "core/default_scene.h"
#include "core/scene.h"
#include "eval/reference_comparison.h"
#include "eval/render_case.h"
#include "reference/reference_scene.h"
#include "render/frame_renderer.h"
#include "render/render_scene.h"
#include "test_support.h"

namespace voxr {
namespace {

Scene scene_file(const std::string& name) {
  return load_scene(std::string(VOXR_SOURCE_DIR) + "/data/scenes/" + name);
}

struct Measured {
  RefractionError error;
  FrameError frame;
};

// voxel-exact at `resolution` with exact shadows, measured against the matched reference.
Measured measure(RenderCase& c, uint32_t resolution) {
  ReferenceFrame reference;
  reference.refraction = render_refraction_reference(c.reference().scene(), c.render_materials(), c.light(),
                                                     c.environment(), c.camera(), ReferenceModel::kMatched);
  FrameRenderer renderer(test::runtime());
  renderer.set_scene(c.soup(), c.materials(), &c.reference());
  renderer.set_environment(c.environment());
  RenderOptions o;
  o.shadows = ShadowMethod::kReference;
  o.refraction.method = RefractionMethod::kVoxelExact;
  o.refraction.resolution = resolution;
  o.keep_samples = true;
  renderer.prepare(o);
  const RenderedFrame frame = renderer.render(c.light(), c.camera(), o);
  Measured m;
  m.frame = measure_against_reference(frame, reference);
  EXPECT_TRUE(m.frame.refraction.has_value());
  if (m.frame.refraction) m.error = *m.frame.refraction;
  return m;
}

void expect_targets(RenderCase& c, const std::string& what) {
  for (uint32_t resolution : {64u, 256u}) {
    const Measured m = measure(c, resolution);
    SCOPED_TRACE(what + " at " + std::to_string(resolution));
    EXPECT_GT(m.error.refracted_pixels, 100u);
    EXPECT_GE(m.error.psnr, 40.0) << "image RMSE " << m.error.rmse;
    EXPECT_LE(m.error.event_mismatch_share, 0.01) << "of " << m.error.refracted_pixels << " pixels";
    EXPECT_EQ(m.error.nonfinite_pixels, 0u);
  }
}

// Where glass touches an opaque surface or another glass, voxel-exact follows the reference's rule for
// touching surfaces (ReferenceScene::intersect_leaving, issue 19 item 4: skip the triangles left, count
// every other surface from just behind the point, coincident hits to the opaque one, then the lowest id);
// the reference before that rule skipped 1e-4 of the scene after every surface and escaped under the floor
// (39.7 dB, 3.2 % event mismatch on thin-vase-floor against it).
template <class Reference>
constexpr bool kReferenceHasContactRule = requires(const Reference& r, std::span<const uint32_t> ids) {
  r.intersect_leaving(glm::vec3(0.0f), glm::vec3(1.0f), ids);
};

TEST(VoxelExactRefraction, RefractionScenesMeetTheTargets) {
  for (const char* name : {"glass-sphere.json", "glass-vase.json"}) {
    RenderCase c(scene_file(name), 160, 120);
    expect_targets(c, name);
  }
}

TEST(VoxelExactRefraction, DefaultAndBunnyScenesMeetTheTargets) {
  {
    RenderCase c(default_scene(), 160, 120);
    expect_targets(c, "default scene");
  }
  const std::string bunny = test::mesh_path("bunny.obj");
  if (bunny.empty()) GTEST_SKIP() << "bunny.obj missing: run scripts/fetch-meshes.sh";
  RenderCase c(scene_file("bunny-glass-130.json"), 160, 120);
  expect_targets(c, "bunny-glass-130");
}

// A glass slab half a voxel thick (the scene spans 8 units: a voxel is 1/8 unit at 64, the slab 1/16) in
// front of an opaque wall, and a glass box and a water box sharing a face: the slab's two faces lie in one
// voxel, the shared face is met by both boxes.
Scene thin_and_touching() {
  return parse_scene(R"({
    "materials": [
      {"name": "wall", "kind": "opaque", "color": [0.7, 0.6, 0.5]},
      {"name": "glass", "kind": "dielectric", "ior": 1.5, "absorption": [0.3, 0.1, 0.05]},
      {"name": "water", "kind": "dielectric", "ior": 1.33, "absorption": [0.05, 0.1, 0.3]}
    ],
    "meshes": [
      {"generator": "box", "params": {"lo": [-4, -2, -3], "hi": [4, 2, -2.9]}, "material": "wall"},
      {"generator": "box", "params": {"lo": [-2, -1, -0.03125], "hi": [0, 1, 0.03125]}, "material": "glass"},
      {"generator": "box", "params": {"lo": [0.5, -1, -0.5], "hi": [1.5, 0, 0.5]}, "material": "glass"},
      {"generator": "box", "params": {"lo": [0.5, 0, -0.5], "hi": [1.5, 1, 0.5]}, "material": "water"}
    ],
    "light": {"type": "directional", "direction": [-0.4, -1, -0.5], "intensity": [0.8, 0.8, 0.8]},
    "camera": {"position": [0.3, 0.8, 4.5], "look_at": [-0.2, 0, 0], "fov_deg": 45},
    "environment": {"procedural": "checker"}
  })",
                     "thin wall and touching dielectrics", ".");
}

TEST(VoxelExactRefraction, ContactScenesMeetTheTargets) {
  if (!kReferenceHasContactRule<ReferenceScene>) GTEST_SKIP() << "the reference lacks the contact rule";
  RenderCase vase(scene_file("thin-vase-floor.json"), 160, 120);
  expect_targets(vase, "thin-vase-floor.json");
  RenderCase c(thin_and_touching(), 160, 120);
  const Measured m = measure(c, 64);
  EXPECT_GT(m.error.refracted_pixels, 1000u);
  EXPECT_GE(m.error.psnr, 40.0) << "image RMSE " << m.error.rmse;
  EXPECT_LE(m.error.event_mismatch_share, 0.01);
  EXPECT_EQ(m.error.nonfinite_pixels, 0u);
}

}  // namespace
}  // namespace voxr
