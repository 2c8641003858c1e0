// Transparent shadow maps from the light's voxel grid against hand-computed transmittance: a leaf over a
// floor, a glass slab, an opaque blocker, under directional and point lights, in centre and conservative
// mode, and the uniform method's constant.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/generators.h"
#include "render/light_frame.h"
#include "render/light_space_maps.h"
#include "render/render_scene.h"
#include "render/transparent_shadow_map.h"
#include "test_support.h"

namespace voxr {
namespace {

struct ShadowCase {
  TriangleSoup soup;
  std::vector<Material> materials;
  Light light;
};

Material sheet(glm::vec3 t) {
  Material m;
  m.name = "leaf";
  m.kind = MaterialKind::kSheet;
  m.transmittance = t;
  return m;
}

// Transmittance at floor points `points` (y = 0, normal +y) by the voxel or uniform method
// (TransparentShadowMap) or the filter or opaque map (LightSpaceMaps).
// `receivers` defaults to the soup's bounds.
std::vector<glm::vec3> shadow_at(const ShadowCase& c, const std::vector<glm::vec3>& points, uint32_t res,
                                 const ShadowMapOptions& options, const Bounds* receivers = nullptr) {
  ClRuntime& cl = test::runtime();
  const RenderLight light = render_light(c.light, kDefaultEnvironment, c.soup.anchor);
  const LightFrame frame = fit_light_frame(light, receivers ? *receivers : c.soup.bounds(), c.soup, res);
  const std::vector<RenderMaterial> mats = render_materials(c.materials);
  cl::Buffer materials = cl.buffer(mats.size() * sizeof(RenderMaterial), "materials");
  cl.upload(materials, mats.data(), mats.size() * sizeof(RenderMaterial), "upload materials");
  std::vector<SurfaceSample> samples(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    SurfaceSample& s = samples[i];
    s = SurfaceSample{};
    for (int a = 0; a < 3; ++a) s.position[a] = points[i][a];
    s.normal[1] = s.geometric_normal[1] = 1.0f;
    s.triangle = 0;
    s.material = 0;
  }
  cl::Buffer sample_buffer = cl.buffer(samples.size() * sizeof(SurfaceSample), "samples");
  cl.upload(sample_buffer, samples.data(), samples.size() * sizeof(SurfaceSample), "upload samples");
  cl::Buffer out = cl.buffer(samples.size() * 16, "transmittance");
  const uint32_t n = uint32_t(samples.size()), m = uint32_t(mats.size());
  if (options.method == ShadowMethod::kFilter || options.method == ShadowMethod::kOpaque) {
    DeviceMesh mesh(cl, c.soup);
    LightSpaceMaps maps(cl);
    maps.build(mesh, frame, light, materials, m, options.method);
    maps.lookup(sample_buffer, n, materials, m, light, options.bias, options.normal_offset, out);
  } else {
    const TriangleSoup projected = frame.projective() ? project_to_light_grid(c.soup, frame) : TriangleSoup{};
    DeviceMesh mesh = upload_mesh(cl, frame.projective() ? projected : c.soup, frame.grid, SplitCull::kGrid);
    Voxelizer voxelizer(cl);
    TransparentShadowMap map(cl, voxelizer);
    const UniformAbsorption u = uniform_absorption(c.soup, c.materials);
    map.build(mesh, frame, materials, m, u.at(frame.params.voxel_size), u.blocks(), options);
    map.lookup(sample_buffer, n, materials, m, light, options, out);
  }
  std::vector<glm::vec4> t(samples.size());
  cl.download(out, t.data(), t.size() * 16, "download transmittance");
  cl.finish();
  std::vector<glm::vec3> rgb;
  for (const glm::vec4& v : t) rgb.emplace_back(v);
  return rgb;
}

ShadowCase leaf_over_floor(const Light& light) {
  ShadowCase c;
  Material floor;
  floor.name = "floor";
  c.materials = {floor, sheet({0.5f, 0.7f, 0.9f})};
  test::add_square(c.soup, 0.0f, -2.0f, 2.0f, 0);
  test::add_square(c.soup, 1.0f, -0.5f, 0.5f, 1);
  c.light = light;
  return c;
}

void expect_near3(glm::vec3 actual, glm::vec3 expected, float tol, const char* what) {
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(actual[a], expected[a], tol) << what << " channel " << a;
}

TEST(TransparentShadowMap, LeafOverFloorUnderDirectionalLight) {
  Light light;
  light.type = "directional";
  light.direction = {0.0f, -1.0f, 0.0f};
  const ShadowCase c = leaf_over_floor(light);
  const std::vector<glm::vec3> points = {{0, 0, 0}, {0.2f, 0, -0.3f}, {1.5f, 0, 1.5f}, {-1.2f, 0, 0.1f}};
  for (RasterMode mode : {RasterMode::kCenter}) {
    ShadowMapOptions o;
    o.mode = mode;
    const auto t = shadow_at(c, points, 64, o);
    // 10-bit quantization of the stored transmittance: 1/2046.
    expect_near3(t[0], {0.5f, 0.7f, 0.9f}, 2e-3f, "under the leaf");
    expect_near3(t[1], {0.5f, 0.7f, 0.9f}, 2e-3f, "under the leaf");
    expect_near3(t[2], {1, 1, 1}, 2e-3f, "beside the leaf");
    expect_near3(t[3], {1, 1, 1}, 2e-3f, "beside the leaf");
  }
}

TEST(TransparentShadowMap, LeafOverFloorUnderPointLight) {
  Light light;
  light.type = "point";
  light.position = {0.1f, 4.0f, 0.2f};
  const ShadowCase c = leaf_over_floor(light);
  const std::vector<glm::vec3> points = {{0, 0, 0}, {0.3f, 0, -0.2f}, {1.8f, 0, 1.8f}};
  const auto t = shadow_at(c, points, 128, ShadowMapOptions{});
  expect_near3(t[0], {0.5f, 0.7f, 0.9f}, 2e-3f, "under the leaf");
  expect_near3(t[1], {0.5f, 0.7f, 0.9f}, 2e-3f, "under the leaf");
  expect_near3(t[2], {1, 1, 1}, 2e-3f, "outside the shadow");
}

TEST(TransparentShadowMap, TwoLeavesInOneVoxelCountTwice) {
  Light light;
  light.type = "directional";
  light.direction = {0.0f, -1.0f, 0.0f};
  ShadowCase c = leaf_over_floor(light);
  test::add_square(c.soup, 1.001f, -0.5f, 0.5f, 1);  // a second leaf within the first one's voxels
  const auto t = shadow_at(c, {{0.1f, 0, 0.1f}}, 64, ShadowMapOptions{});
  expect_near3(t[0], {0.25f, 0.49f, 0.81f}, 2e-3f, "under both leaves");
}

TEST(TransparentShadowMap, ConservativeModeOverCountsAndUniformUsesOneConstant) {
  Light light;
  light.type = "directional";
  light.direction = {0.6f, -1.0f, 0.2f};
  const ShadowCase c = leaf_over_floor(light);
  // Floor points in the leaf's shadow (the light moves it by (0.6, 0.2) per unit of height).
  std::vector<glm::vec3> points;
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j) points.push_back({0.6f + 0.1f * float(i), 0.0f, 0.2f + 0.1f * float(j)});
  ShadowMapOptions o;
  o.mode = RasterMode::kConservative;
  const auto conservative = shadow_at(c, points, 64, o);
  // A leaf tilted against the light's slicing axis covers up to two voxels of a column in conservative mode:
  // crossings counted twice on average darken the shadow.
  float mean = 0.0f;
  for (const glm::vec3& t : conservative) mean += t.x / float(points.size());
  EXPECT_LT(mean, 0.5f - 0.02f);
  o.mode = RasterMode::kCenter;
  for (const glm::vec3& t : shadow_at(c, points, 64, o)) expect_near3(t, {0.5f, 0.7f, 0.9f}, 2e-3f, "centre");
  o.method = ShadowMethod::kUniform;
  // One sheet material: the constant is its own optical depth, and the slicemap's one voxel per crossing
  // gives t.
  for (const glm::vec3& t : shadow_at(c, points, 64, o))
    expect_near3(t, {0.5f, 0.7f, 0.9f}, 2e-3f, "uniform");
}

ShadowCase glass_and_wall(const Light& light) {
  ShadowCase c;
  Material floor, glass, wall;
  floor.name = "floor";
  glass.name = "glass";
  glass.kind = MaterialKind::kDielectric;
  glass.absorption = {0.4f, 0.8f, 1.6f};
  wall.name = "wall";
  c.materials = {floor, glass, wall};
  test::add_square(c.soup, 0.0f, -2.0f, 2.0f, 0);
  c.soup.append(test::box_soup({-1.5f, 0.5f, -0.5f}, {-0.5f, 1.0f, 0.5f}), glm::mat4(1.0f), 1);  // d = 0.5
  c.soup.append(test::box_soup({0.5f, 0.5f, -0.5f}, {1.5f, 1.0f, 0.5f}), glm::mat4(1.0f), 2);
  c.light = light;
  return c;
}

TEST(TransparentShadowMap, GlassSlabAbsorbsAlongItsThicknessAndOpaqueBlocks) {
  Light light;
  light.type = "directional";
  light.direction = {0.0f, -1.0f, 0.0f};
  const ShadowCase c = glass_and_wall(light);
  const glm::vec3 expected = glm::exp(-c.materials[1].absorption * 0.5f);
  const std::vector<glm::vec3> points = {{-1.0f, 0, 0.0f}, {1.0f, 0, 0.0f}, {0.0f, 0, 1.5f}};
  for (ShadowMethod method : {ShadowMethod::kVoxel, ShadowMethod::kFilter}) {
    for (RasterMode mode : {RasterMode::kCenter, RasterMode::kConservative}) {
      if (method == ShadowMethod::kFilter && mode == RasterMode::kConservative) continue;
      ShadowMapOptions o;
      o.method = method;
      o.mode = mode;
      const auto t = shadow_at(c, points, 128, o);
      const std::string what = std::string(shadow_method_info(method).name) + " " + raster_mode_name(mode);
      // The voxel method resolves the glass's two faces to half a slab each; the filter map is exact up to
      // its fixed point (1/1024 of optical depth).
      expect_near3(t[0], expected, method == ShadowMethod::kVoxel ? 0.02f * 1.6f * 4.0f : 2e-3f,
                   (what + ": under the glass").c_str());
      expect_near3(t[1], {0, 0, 0}, 1e-6f, (what + ": under the opaque box").c_str());
      expect_near3(t[2], {1, 1, 1}, 2e-3f, (what + ": in the open").c_str());
    }
  }
  ShadowMapOptions o;
  o.method = ShadowMethod::kOpaque;
  const auto t = shadow_at(c, points, 128, o);
  expect_near3(t[0], {0, 0, 0}, 1e-6f, "opaque map: glass blocks");
  expect_near3(t[2], {1, 1, 1}, 1e-6f, "opaque map: in the open");
}

TEST(TransparentShadowMap, ACasterReachingPastThePointLightStillShadows) {
  // A wall at x = 1 from y = -1 to 9 passes beside the light at (0, 5, 0): the ray to (1.5, 0, 0) crosses it
  // at y = 1.67, nearer the light than any other caster's vertex.
  Light light;
  light.type = "point";
  light.position = {0.0f, 5.0f, 0.0f};
  ShadowCase c;
  Material floor, wall;
  floor.name = "floor";
  wall.name = "wall";
  c.materials = {floor, wall};
  test::add_square(c.soup, 0.0f, -2.0f, 2.0f, 0);
  const uint32_t b = uint32_t(c.soup.positions.size());
  c.soup.positions.push_back({1.0f, -1.0f, -1.0f, 1});
  c.soup.positions.push_back({1.0f, 9.0f, -1.0f, 1});
  c.soup.positions.push_back({1.0f, 9.0f, 1.0f, 1});
  c.soup.positions.push_back({1.0f, -1.0f, 1.0f, 1});
  c.soup.triangles.push_back({b, b + 1, b + 2, 1});
  c.soup.triangles.push_back({b, b + 2, b + 3, 1});
  c.light = light;
  for (ShadowMethod method : {ShadowMethod::kVoxel, ShadowMethod::kOpaque}) {
    ShadowMapOptions o;
    o.method = method;
    Bounds floor;  // the receivers: the light is outside them, the wall reaches past it
    floor.extend({-2.0f, 0.0f, -2.0f});
    floor.extend({2.0f, 0.0f, 2.0f});
    const auto t = shadow_at(c, {{1.5f, 0.0f, 0.0f}, {0.5f, 0.0f, 0.0f}}, 128, o, &floor);
    expect_near3(t[0], {0, 0, 0}, 1e-6f, "behind the wall");
    expect_near3(t[1], {1, 1, 1}, 2e-3f, "in front of the wall");
  }
}

}  // namespace
}  // namespace voxr
