// `--shadows voxel-exact` (render/techniques/voxel_exact_shadows.cpp, shadow_exact.cl) against the exact
// reference (ReferenceScene::transmittance), which it reproduces: whole frames of the shadow and glass
// scenes at light grids 64 and 256 (transmittance RMSE <= 0.005 at the receivers, the issue's target), and
// single shadow rays placed where the rules matter: a receiver on a floor under a glass box standing on it
// (it starts inside the glass), a sheet crossed through its shared edges and vertices (one crossing), a
// grazed fold (none).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/default_scene.h"
#include "core/scene.h"
#include "eval/render_case.h"
#include "metrics/image_metrics.h"
#include "metrics/shadow_receivers.h"
#include "reference/reference_scene.h"
#include "render/frame_renderer.h"
#include "render/render_scene.h"
#include "render/technique.h"
#include "render/triangle_grid.h"
#include "test_lights.h"
#include "test_support.h"
#include "voxelize/device_mesh.h"
#include "voxelize/voxelizer.h"

namespace voxr {
namespace {

// A floor, a low opaque box and a leaf under a directional light 85 degrees from the vertical (the
// stability suite's grazing-light scene).
constexpr std::string_view kGrazingFloor = R"({
  "materials": [
    {"name": "floor", "kind": "opaque", "color": [0.75, 0.75, 0.72]},
    {"name": "stone", "kind": "opaque", "color": [0.6, 0.6, 0.65]},
    {"name": "leaf", "kind": "sheet", "color": [0.35, 0.6, 0.2], "transmittance": [0.5, 0.75, 0.4]}
  ],
  "meshes": [
    {"generator": "plane", "params": {"size": [6, 6], "subdivisions": 1}, "material": "floor"},
    {"generator": "box", "params": {"lo": [-0.15, 0, -0.15], "hi": [0.15, 0.2, 0.15]}, "material": "stone",
     "transform": {"rotate_deg": [0, 20, 0], "translate": [-1.2, 0, -0.4]}},
    {"generator": "plane", "params": {"size": [0.5, 0.5], "subdivisions": 1}, "material": "leaf",
     "transform": {"rotate_deg": [25, 10, 0], "translate": [-1.0, 0.2, 0.5]}}
  ],
  "light": {"type": "directional", "direction": [0.9962, -0.0872, 0], "intensity": [1.2, 1.2, 1.2]},
  "camera": {"position": [0.5, 3.0, 3.5], "look_at": [0.5, 0, 0], "fov_deg": 45, "width": 640,
             "height": 480},
  "environment": {"color": [0.3, 0.35, 0.4]}
})";

Scene scene_named(const std::string& name) {
  if (name == "default") return default_scene();
  if (name == "grazing-floor") return parse_scene(kGrazingFloor, "grazing floor", ".");
  return load_scene(std::string(VOXR_SOURCE_DIR) + "/data/scenes/" + name + ".json");
}

struct FrameCase {
  const char* scene;
  uint32_t res;
};

class ExactShadowFrames : public ::testing::TestWithParam<FrameCase> {};

// The primary samples of a 128 x 96 frame (no refraction: every visible receiver is a primary sample, and
// behind glass the shadow rays cross it), voxel-exact's transmittance there against the reference's.
TEST_P(ExactShadowFrames, MatchTheReference) {
  RenderCase c(scene_named(GetParam().scene), 128, 96);
  FrameRenderer renderer(test::runtime());
  renderer.set_scene(c.soup(), c.materials());
  renderer.set_environment(c.environment());
  RenderOptions o;
  o.shadows = ShadowMethod::kVoxelExact;
  o.shadow_resolution = GetParam().res;
  o.refraction.method = RefractionMethod::kNone;
  o.keep_samples = true;
  renderer.prepare(o);
  const RenderedFrame frame = renderer.render(c.light(), c.camera(), o);
  const ReferenceScene reference(c.soup(), c.materials());
  const std::vector<glm::vec3> exact = reference.transmittance(c.light(), frame.samples);
  const std::vector<uint8_t> mask = shadow_receivers(frame.samples, c.render_materials(), c.light());
  const TransmittanceError e = transmittance_error(frame.transmittance, exact, mask, 0.05);
  ASSERT_GT(e.receivers, 3000u);
  // The exact shadow is not all lit or all dark: the case measures something.
  uint64_t shadowed = 0;
  for (size_t i = 0; i < exact.size(); ++i) shadowed += mask[i] && exact[i].x < 0.99f;
  EXPECT_GT(shadowed, 50u);
  EXPECT_LE(e.rmse, 0.005) << "max |difference| " << e.max_abs << ", over 0.05: " << e.share_over_threshold;
  for (const glm::vec4& p : frame.image.pixels)
    ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
  // Deterministic: the same frame again gives the same transmittance, bit for bit.
  EXPECT_EQ(renderer.render(c.light(), c.camera(), o).transmittance, frame.transmittance);
}

INSTANTIATE_TEST_SUITE_P(Scenes, ExactShadowFrames,
                         ::testing::Values(FrameCase{"shadow-tree", 64}, FrameCase{"shadow-tree", 256},
                                           FrameCase{"shadow-tree-directional", 64},
                                           FrameCase{"shadow-tree-directional", 256},
                                           FrameCase{"glass-sphere", 64}, FrameCase{"glass-sphere", 256},
                                           FrameCase{"thin-vase-floor", 64},
                                           FrameCase{"thin-vase-floor", 256}, FrameCase{"default", 64},
                                           FrameCase{"default", 256}, FrameCase{"grazing-floor", 64},
                                           FrameCase{"grazing-floor", 256}),
                         [](const ::testing::TestParamInfo<FrameCase>& p) {
                           std::string s = std::string(p.param.scene) + "_" + std::to_string(p.param.res);
                           for (char& ch : s)
                             if (ch == '-') ch = '_';
                           return s;
                         });

// ---- single shadow rays ----

// The voxel-exact technique run by hand on chosen receivers (the frame renderer's samples come from the
// camera): a FrameContext over `soup`, one build and one lookup.
class ExactRays {
 public:
  ExactRays(TriangleSoup soup, std::vector<Material> materials)
      : soup_(std::move(soup)),
        materials_(std::move(materials)),
        voxelizer_(cl_),
        grids_(cl_, voxelizer_),
        mesh_(cl_, soup_),
        reference_(soup_, materials_) {
    const std::vector<RenderMaterial> m = render_materials(materials_);
    materials_buffer_ = cl_.buffer(m.size() * sizeof(RenderMaterial), "materials");
    cl_.upload(materials_buffer_, m.data(), m.size() * sizeof(RenderMaterial), "upload materials");
  }

  // Receiver i lies at points[i] on triangle selves[i]; its transmittance towards `light` by voxel-exact at
  // light grid `res`.
  std::vector<glm::vec3> exact(const RenderLight& light, const std::vector<glm::vec3>& points,
                               const std::vector<uint32_t>& selves, uint32_t res) {
    std::vector<SurfaceSample> samples(points.size());
    for (size_t i = 0; i < points.size(); ++i) {
      SurfaceSample& s = samples[i];
      for (int a = 0; a < 3; ++a) s.position[a] = points[i][a];
      s.triangle = selves[i];
      s.material = soup_.triangles[selves[i]].w;
    }
    RenderOptions o;
    o.shadows = ShadowMethod::kVoxelExact;
    o.shadow_resolution = res;
    std::unique_ptr<ShadowTechnique> technique = make_shadow_technique(cl_, voxelizer_, o.shadows);
    cl_.build_programs(technique->programs(o));
    technique->prepare(o);
    FrameStats stats;
    FrameContext ctx;
    ctx.cl = &cl_;
    ctx.soup = &soup_;
    ctx.mesh = &mesh_;
    ctx.materials = &materials_buffer_;
    ctx.material_count = uint32_t(materials_.size());
    ctx.host_materials = &materials_;
    ctx.light = &light;
    ctx.pixels = samples.size();
    ctx.stats = &stats;
    ctx.triangle_grids = &grids_;
    technique->set_scene(ctx);
    grids_.begin_frame();
    technique->build(ctx, o);
    cl::Buffer ends = cl_.buffer(samples.size() * sizeof(SurfaceSample), "samples");
    cl_.upload(ends, samples.data(), samples.size() * sizeof(SurfaceSample), "upload samples");
    cl::Buffer out = cl_.buffer(samples.size() * 16, "transmittance");
    technique->lookup(ctx, o, ends, out);
    std::vector<glm::vec4> t(samples.size());
    cl_.download(out, t.data(), t.size() * 16, "download transmittance");
    cl_.finish();
    std::vector<glm::vec3> rgb(t.size());
    for (size_t i = 0; i < t.size(); ++i) rgb[i] = glm::vec3(t[i]);
    return rgb;
  }

  glm::vec3 reference(const RenderLight& light, const glm::vec3& point, uint32_t self) const {
    return reference_.transmittance(light, point, self);
  }

 private:
  ClRuntime& cl_ = test::runtime();
  TriangleSoup soup_;
  std::vector<Material> materials_;
  Voxelizer voxelizer_;
  TriangleGrids grids_;
  DeviceMesh mesh_;
  ReferenceScene reference_;
  cl::Buffer materials_buffer_;
};

Material opaque() {
  Material m;
  m.name = "floor";
  m.kind = MaterialKind::kOpaque;
  m.color = glm::vec3(0.8f);
  return m;
}
Material glass(glm::vec3 absorption) {
  Material m;
  m.name = "glass";
  m.kind = MaterialKind::kDielectric;
  m.ior = 1.5f;
  m.absorption = absorption;
  return m;
}
Material sheet(glm::vec3 transmittance) {
  Material m;
  m.name = "sheet";
  m.kind = MaterialKind::kSheet;
  m.color = glm::vec3(0.5f);
  m.transmittance = transmittance;
  return m;
}

// Which of the two triangles add_square made at `first` holds (x, z) (they share the diagonal lo-lo to
// hi-hi: x >= z lies in the first).
uint32_t square_triangle(uint32_t first, float x, float z) {
  return x >= z ? first : first + 1;
}

// A glass box standing exactly on a floor (its bottom face in the floor's plane, as in the built-in scene):
// a receiver on the floor under it lies on the glass's surface, and the shadow ray starts inside the glass.
// The hits on the coplanar bottom face lie at t = 0 (ignored, as the reference ignores them), so the
// crossings' parity over the whole ray says "inside": exp(-sigma_a x the path up through the box).
TEST(ExactShadowRays, ReceiverUnderAGlassBoxStandingOnTheFloor) {
  const glm::vec3 sigma(0.5f, 1.0f, 2.0f);
  TriangleSoup soup;
  test::add_square(soup, 0.0f, -3.0f, 3.0f, 0);  // triangles 0, 1
  soup.append(test::box_soup(glm::vec3(-0.5f, 0.0f, -0.5f), glm::vec3(0.5f, 1.0f, 0.5f)), glm::mat4(1.0f), 1);
  ExactRays rays(std::move(soup), {opaque(), glass(sigma)});
  for (const glm::vec3 dir : {glm::vec3(0.0f, -1.0f, 0.0f), glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f))}) {
    const RenderLight light = test::directional_light(dir);
    std::vector<glm::vec3> points;
    std::vector<uint32_t> selves;
    // Receivers whose ray leaves the box through its top under both lights.
    for (float x = -0.15f; x <= 0.36f; x += 0.1f)
      for (float z = -0.15f; z <= 0.36f; z += 0.1f) {
        points.emplace_back(x, 0.0f, z);
        selves.push_back(square_triangle(0, x, z));
      }
    points.emplace_back(2.0f, 0.0f, 2.0f);  // beside the box: lit
    selves.push_back(0);
    for (uint32_t res : {64u, 256u}) {
      const std::vector<glm::vec3> t = rays.exact(light, points, selves, res);
      for (size_t i = 0; i + 1 < points.size(); ++i) {
        const float length = 1.0f / -dir.y;  // up through the top face
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(t[i][c], std::exp(-sigma[c] * length), 1e-5f) << "receiver " << i << " res " << res;
        const glm::vec3 r = rays.reference(light, points[i], selves[i]);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(t[i][c], r[c], 1e-5f) << "receiver " << i << " res " << res;
      }
      EXPECT_EQ(t.back(), glm::vec3(1.0f));
    }
  }
}

// A point light inside the glass box: the ray goes on past the light to count the crossings beyond it, so a
// receiver beside the box starts outside (attenuated from where it enters to the light) and one under the box
// inside (attenuated all the way).
TEST(ExactShadowRays, PointLightInsideGlass) {
  const glm::vec3 sigma(0.5f, 1.0f, 2.0f);
  TriangleSoup soup;
  test::add_square(soup, 0.0f, -3.0f, 3.0f, 0);  // triangles 0, 1
  soup.append(test::box_soup(glm::vec3(-0.5f, 0.0f, -0.5f), glm::vec3(0.5f, 1.0f, 0.5f)), glm::mat4(1.0f), 1);
  ExactRays rays(std::move(soup), {opaque(), glass(sigma)});
  const glm::vec3 light_at(0.0f, 0.5f, 0.0f);
  const RenderLight light = test::point_light(light_at);
  const std::vector<glm::vec3> points = {{2.0f, 0.0f, 0.0f}, {0.2f, 0.0f, 0.1f}};
  const std::vector<uint32_t> selves = {0, 0};
  // Beside: enters through the face x = 0.5 a quarter of the way from the light; under: inside all along.
  const std::vector<float> inside = {0.25f * glm::length(light_at - points[0]),
                                     glm::length(light_at - points[1])};
  for (uint32_t res : {64u, 256u}) {
    const std::vector<glm::vec3> t = rays.exact(light, points, selves, res);
    for (size_t i = 0; i < points.size(); ++i) {
      const glm::vec3 r = rays.reference(light, points[i], selves[i]);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(t[i][c], std::exp(-sigma[c] * inside[i]), 1e-5f) << "receiver " << i << " res " << res;
        EXPECT_NEAR(t[i][c], r[c], 1e-5f) << "receiver " << i << " res " << res;
      }
    }
  }
}

// A sheet fan (8 triangles round one centre vertex, vertices shared) above a floor, the light straight down:
// rays through the centre vertex, through shared edges and through faces each cross the sheet once
// (transmittance t, not t^2 or t^8).
TEST(ExactShadowRays, SheetCrossedThroughSharedEdgesAndAVertexCountsOnce) {
  const glm::vec3 transmit(0.5f, 0.6f, 0.7f);
  TriangleSoup soup;
  test::add_square(soup, 0.0f, -3.0f, 3.0f, 0);  // triangles 0, 1
  const uint32_t centre = uint32_t(soup.positions.size());
  soup.positions.push_back({0.0f, 1.0f, 0.0f, 1.0f});
  const float ring[8][2] = {{0.5f, 0.0f},  {0.5f, 0.5f},   {0.0f, 0.5f},  {-0.5f, 0.5f},
                            {-0.5f, 0.0f}, {-0.5f, -0.5f}, {0.0f, -0.5f}, {0.5f, -0.5f}};
  for (const auto& r : ring) soup.positions.push_back({r[0], 1.0f, r[1], 1.0f});
  for (uint32_t i = 0; i < 8; ++i)
    soup.triangles.push_back({centre, centre + 1 + i, centre + 1 + (i + 1) % 8, 1});
  ExactRays rays(std::move(soup), {opaque(), sheet(transmit)});
  const RenderLight light = test::directional_light(glm::vec3(0.0f, -1.0f, 0.0f));
  // The centre vertex; edges along x, z and the diagonals; two face interiors; one beside the sheet.
  const std::vector<glm::vec3> points = {{0.0f, 0.0f, 0.0f},   {0.25f, 0.0f, 0.0f},     {0.0f, 0.0f, -0.25f},
                                         {0.25f, 0.0f, 0.25f}, {-0.125f, 0.0f, 0.125f}, {0.3f, 0.0f, 0.1f},
                                         {-0.1f, 0.0f, -0.3f}, {1.0f, 0.0f, 1.0f}};
  std::vector<uint32_t> selves;
  for (const glm::vec3& p : points) selves.push_back(square_triangle(0, p.x, p.z));
  for (uint32_t res : {64u, 256u}) {
    const std::vector<glm::vec3> t = rays.exact(light, points, selves, res);
    for (size_t i = 0; i + 1 < points.size(); ++i) {
      EXPECT_EQ(t[i], transmit) << "receiver " << i << " res " << res;
      EXPECT_EQ(rays.reference(light, points[i], selves[i]), transmit) << "receiver " << i;
    }
    EXPECT_EQ(t.back(), glm::vec3(1.0f));
  }
}

// A sheet roof (two triangles sharing the ridge) and a ray grazing the ridge with both faces below it: it
// touches the surface, crossing nothing (1); a ray through both faces lower down crosses twice (t^2).
TEST(ExactShadowRays, GrazedRidgeIsNoCrossing) {
  const glm::vec3 transmit(0.5f, 0.6f, 0.7f);
  TriangleSoup soup;
  // A wall x = -2 facing +x (triangles 0, 1), the receivers on it.
  soup.positions.push_back({-2.0f, -1.0f, -1.0f, 1.0f});
  soup.positions.push_back({-2.0f, 3.0f, -1.0f, 1.0f});
  soup.positions.push_back({-2.0f, 3.0f, 1.0f, 1.0f});
  soup.positions.push_back({-2.0f, -1.0f, 1.0f, 1.0f});
  soup.triangles.push_back({0, 1, 2, 0});
  soup.triangles.push_back({0, 2, 3, 0});
  // The roof: ridge x = 0, y = 1 along z, eaves at x = +-0.5, y = 0.5.
  const uint32_t b = uint32_t(soup.positions.size());
  for (const float z : {-0.5f, 0.5f}) {
    soup.positions.push_back({0.0f, 1.0f, z, 1.0f});
    soup.positions.push_back({-0.5f, 0.5f, z, 1.0f});
    soup.positions.push_back({0.5f, 0.5f, z, 1.0f});
  }
  soup.triangles.push_back({b, b + 1, b + 4, 1});  // west face
  soup.triangles.push_back({b, b + 4, b + 3, 1});
  soup.triangles.push_back({b, b + 5, b + 2, 1});  // east face
  soup.triangles.push_back({b, b + 3, b + 5, 1});
  ExactRays rays(std::move(soup), {opaque(), sheet(transmit)});
  const RenderLight light = test::directional_light(glm::vec3(-1.0f, 0.0f, 0.0f));  // travelling along -x
  const std::vector<glm::vec3> points = {{-2.0f, 1.0f, 0.25f}, {-2.0f, 0.75f, 0.125f}, {-2.0f, 1.5f, 0.0f}};
  const std::vector<uint32_t> selves = {0, 0, 0};
  const std::vector<glm::vec3> expected = {glm::vec3(1.0f), transmit * transmit, glm::vec3(1.0f)};
  for (uint32_t res : {64u, 256u}) {
    const std::vector<glm::vec3> t = rays.exact(light, points, selves, res);
    for (size_t i = 0; i < points.size(); ++i) {
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(t[i][c], expected[i][c], 1e-6f) << "receiver " << i << " res " << res;
      const glm::vec3 r = rays.reference(light, points[i], selves[i]);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(r[c], expected[i][c], 1e-6f) << "receiver " << i;
    }
  }
}

}  // namespace
}  // namespace voxr
