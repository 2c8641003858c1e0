// The Embree reference against hand computations: shadow transmittance through sheets, glass and opaque
// boxes (every crossing once, shared edges and vertices included), point-light falloff, primary-ray samples,
// the shaded image, and the vertex normals the shading normal interpolates.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <vector>

#include "core/generators.h"
#include "reference/reference_renderer.h"
#include "reference/reference_scene.h"
#include "render/render_scene.h"
#include "render/shade_host.h"
#include "render/vertex_normals.h"
#include "util/error.h"

namespace voxr {
namespace {

constexpr float kTol = 1e-5f;

constexpr uint32_t kFloor = 0, kLeaf = 1, kGlass = 2, kWall = 3;
const glm::vec3 kLeafT(0.5f, 0.7f, 0.9f);
const glm::vec3 kSigma(0.1f, 0.2f, 0.3f);

std::vector<Material> test_materials() {
  std::vector<Material> m(4);
  m[kFloor].name = "floor";
  m[kFloor].color = glm::vec3(0.5f, 0.6f, 0.7f);
  m[kLeaf].name = "leaf";
  m[kLeaf].kind = MaterialKind::kSheet;
  m[kLeaf].color = glm::vec3(0.2f, 0.8f, 0.3f);
  m[kLeaf].transmittance = kLeafT;
  m[kGlass].name = "glass";
  m[kGlass].kind = MaterialKind::kDielectric;
  m[kGlass].absorption = kSigma;
  m[kWall].name = "wall";
  m[kWall].color = glm::vec3(0.9f);
  return m;
}

uint32_t add_vertex(TriangleSoup& s, glm::vec3 p) {
  s.positions.push_back(glm::vec4(p, 1.0f));
  return uint32_t(s.positions.size() - 1);
}

// Quad a b c d as triangles (a, b, c), (a, c, d): the diagonal a-c is shared.
void add_quad(TriangleSoup& s, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, uint32_t material) {
  const uint32_t i = add_vertex(s, a), j = add_vertex(s, b), k = add_vertex(s, c), l = add_vertex(s, d);
  s.triangles.push_back({i, j, k, material});
  s.triangles.push_back({i, k, l, material});
}

// Floor: y = 0, x and z in [-3, 3], normal +y, diagonal from (-3, -3) to (3, 3) in (x, z).
void add_floor(TriangleSoup& s) {
  add_quad(s, {-3, 0, -3}, {-3, 0, 3}, {3, 0, 3}, {3, 0, -3}, kFloor);
}

// Leaf: y = 1, x and z in [-0.5, 0.5], diagonal from (-0.5, -0.5) to (0.5, 0.5): under it x == z.
void add_leaf(TriangleSoup& s, float y = 1.0f) {
  add_quad(s, {-0.5f, y, -0.5f}, {-0.5f, y, 0.5f}, {0.5f, y, 0.5f}, {0.5f, y, -0.5f}, kLeaf);
}

void add_box(TriangleSoup& s, glm::vec3 lo, glm::vec3 hi, uint32_t material) {
  s.append(make_box(lo, hi), glm::mat4(1.0f), material);
}

RenderLight directional(glm::vec3 direction, glm::vec3 intensity = glm::vec3(1.0f)) {
  RenderLight l{};
  l.directional = 1;
  const glm::vec3 d = glm::normalize(direction);
  for (int c = 0; c < 3; ++c) {
    l.direction[c] = d[c];
    l.intensity[c] = intensity[c];
    l.ambient[c] = 0.1f;
  }
  return l;
}

RenderLight point_light(glm::vec3 position, glm::vec3 intensity) {
  RenderLight l{};
  for (int c = 0; c < 3; ++c) {
    l.position[c] = position[c];
    l.intensity[c] = intensity[c];
    l.ambient[c] = 0.1f;
  }
  return l;
}

glm::vec3 position_of(const SurfaceSample& s) {
  return glm::vec3(s.position[0], s.position[1], s.position[2]);
}
glm::vec3 normal_of(const SurfaceSample& s) {
  return glm::vec3(s.normal[0], s.normal[1], s.normal[2]);
}
glm::vec3 geometric_of(const SurfaceSample& s) {
  return glm::vec3(s.geometric_normal[0], s.geometric_normal[1], s.geometric_normal[2]);
}

// The floor sample at (x, 0, z), found from below (so nothing above hides it): position and triangle.
SurfaceSample floor_sample(const ReferenceScene& scene, float x, float z) {
  const SurfaceSample s = scene.intersect({x, -1.0f, z}, {0.0f, 1.0f, 0.0f});
  EXPECT_NE(s.triangle, VOXR_NO_TRIANGLE);
  EXPECT_EQ(s.material, kFloor);
  return s;
}

glm::vec3 floor_transmittance(const ReferenceScene& scene, const RenderLight& light, float x, float z) {
  const SurfaceSample s = floor_sample(scene, x, z);
  return scene.transmittance(light, position_of(s), s.triangle);
}

// Every channel within kTol.
::testing::AssertionResult near3(const glm::vec3& expected, const glm::vec3& actual) {
  for (int c = 0; c < 3; ++c)
    if (!(std::abs(expected[c] - actual[c]) <= kTol))
      return ::testing::AssertionFailure()
             << "expected (" << expected.x << ", " << expected.y << ", " << expected.z << "), got ("
             << actual.x << ", " << actual.y << ", " << actual.z << ")";
  return ::testing::AssertionSuccess();
}

// (a) One leaf over the floor, light straight down: the leaf's transmittance under it, exactly once under
// its shared diagonal and under its vertices; 1 beside it.
TEST(ReferenceShadow, LeafTransmitsOncePerCrossing) {
  TriangleSoup soup;
  add_floor(soup);
  add_leaf(soup);
  const ReferenceScene scene(soup, test_materials());
  const RenderLight light = directional({0, -1, 0});
  // Inside one triangle or the other.
  EXPECT_TRUE(near3(kLeafT, floor_transmittance(scene, light, 0.3f, -0.2f)));
  EXPECT_TRUE(near3(kLeafT, floor_transmittance(scene, light, -0.3f, 0.2f)));
  // Exactly under the shared diagonal: both triangles report the hit, one crossing.
  for (float a : {0.0f, 0.25f, -0.3f, 0.4999f, -0.125f})
    EXPECT_TRUE(near3(kLeafT, floor_transmittance(scene, light, a, a))) << "under the diagonal at " << a;
  // Exactly under each vertex: the diagonal's ends (both triangles) and the other two (one each).
  for (glm::vec2 v :
       {glm::vec2(-0.5f, -0.5f), glm::vec2(0.5f, 0.5f), glm::vec2(-0.5f, 0.5f), glm::vec2(0.5f, -0.5f)})
    EXPECT_TRUE(near3(kLeafT, floor_transmittance(scene, light, v.x, v.y)))
        << "under vertex " << v.x << " " << v.y;
  // Beside the leaf.
  EXPECT_TRUE(near3(glm::vec3(1.0f), floor_transmittance(scene, light, 0.6f, 0.0f)));
  EXPECT_TRUE(near3(glm::vec3(1.0f), floor_transmittance(scene, light, -2.0f, 2.0f)));
  // A receiver on the leaf itself (self excluded) sees the sky.
  const SurfaceSample on_leaf = scene.intersect({0.1f, 5.0f, 0.2f}, {0.0f, -1.0f, 0.0f});
  ASSERT_EQ(on_leaf.material, kLeaf);
  EXPECT_TRUE(near3(glm::vec3(1.0f), scene.transmittance(light, position_of(on_leaf), on_leaf.triangle)));
}

// (b) Two coincident leaves with vertices of their own: two surfaces, t^2, under the diagonal too.
TEST(ReferenceShadow, CoincidentLeavesAreTwoCrossings) {
  TriangleSoup soup;
  add_floor(soup);
  add_leaf(soup);
  add_leaf(soup);
  const ReferenceScene scene(soup, test_materials());
  const RenderLight light = directional({0, -1, 0});
  EXPECT_TRUE(near3(kLeafT * kLeafT, floor_transmittance(scene, light, 0.3f, -0.2f)));
  EXPECT_TRUE(near3(kLeafT * kLeafT, floor_transmittance(scene, light, 0.1f, 0.1f)));
  EXPECT_TRUE(near3(kLeafT * kLeafT, floor_transmittance(scene, light, -0.5f, -0.5f)));
}

// (c) A closed glass box 0.5 thick along the light: exp(-sigma_a * 0.5). Receivers on or inside the glass
// start inside (the parity over the whole ray says so).
TEST(ReferenceShadow, GlassBoxAbsorbsAlongItsThickness) {
  TriangleSoup soup;
  add_floor(soup);
  add_box(soup, {-0.5f, 1.0f, -0.5f}, {0.5f, 1.5f, 0.5f}, kGlass);
  const ReferenceScene scene(soup, test_materials());
  const RenderLight light = directional({0, -1, 0});
  const glm::vec3 expected = glm::exp(-kSigma * 0.5f);
  EXPECT_TRUE(near3(expected, floor_transmittance(scene, light, 0.1f, 0.2f)));
  // Under the box's face diagonals (shared edges top and bottom) and under its corner.
  EXPECT_TRUE(near3(expected, floor_transmittance(scene, light, 0.2f, 0.2f)));
  EXPECT_TRUE(near3(expected, floor_transmittance(scene, light, 0.2f, -0.2f)));
  EXPECT_TRUE(near3(expected, floor_transmittance(scene, light, -0.5f, -0.5f)));
  EXPECT_TRUE(near3(glm::vec3(1.0f), floor_transmittance(scene, light, 1.0f, 0.0f)));
  // A point inside the glass, 0.25 below the top.
  EXPECT_TRUE(
      near3(glm::exp(-kSigma * 0.25f), scene.transmittance(light, {0.1f, 1.25f, 0.1f}, VOXR_NO_TRIANGLE)));
  // A receiver on the glass's bottom face looks up through the whole box.
  const SurfaceSample bottom = scene.intersect({0.1f, 0.5f, -0.3f}, {0.0f, 1.0f, 0.0f});
  ASSERT_EQ(bottom.material, kGlass);
  EXPECT_TRUE(near3(expected, scene.transmittance(light, position_of(bottom), bottom.triangle)));
  // A glass box resting on the floor (its bottom face in the floor's plane, nearer than the start epsilon).
  TriangleSoup resting;
  add_floor(resting);
  add_box(resting, {-0.5f, 0.0f, -0.5f}, {0.5f, 0.5f, 0.5f}, kGlass);
  const ReferenceScene rest(resting, test_materials());
  EXPECT_TRUE(near3(expected, rest.transmittance(light, {0.1f, 0.0f, 0.2f}, VOXR_NO_TRIANGLE)));
}

// (d) An opaque box blocks; one grazed exactly at an edge does not (the ray touches, does not cross).
TEST(ReferenceShadow, OpaqueBoxBlocks) {
  TriangleSoup soup;
  add_floor(soup);
  add_box(soup, {-0.5f, 1.0f, -0.5f}, {0.5f, 1.5f, 0.5f}, kWall);
  const ReferenceScene scene(soup, test_materials());
  const RenderLight down = directional({0, -1, 0});
  EXPECT_TRUE(near3(glm::vec3(0.0f), floor_transmittance(scene, down, 0.1f, 0.2f)));
  EXPECT_TRUE(near3(glm::vec3(0.0f), floor_transmittance(scene, down, 0.25f, 0.25f)));
  EXPECT_TRUE(near3(glm::vec3(0.0f), floor_transmittance(scene, down, 0.5f, 0.5f)));
  EXPECT_TRUE(near3(glm::vec3(1.0f), floor_transmittance(scene, down, 0.75f, 0.0f)));
  // Light along (1, -1, 0): the ray from (2, 0, z) towards it passes the box's edge x = 0.5, y = 1.5.
  const RenderLight oblique = directional({1, -1, 0});
  EXPECT_TRUE(near3(glm::vec3(1.0f), floor_transmittance(scene, oblique, 2.0f, 0.1f)));
  EXPECT_TRUE(near3(glm::vec3(0.0f), floor_transmittance(scene, oblique, 1.9f, 0.1f)));
  EXPECT_TRUE(near3(glm::vec3(1.0f), floor_transmittance(scene, oblique, 2.1f, 0.1f)));
}

// Rays parallel to two axes that run exactly along a box's edge or through its corner: Embree's node test
// would lose the box there (a bound equal to the origin where the direction is 0); the mirrored casts find
// it.
TEST(ReferenceShadow, AxisParallelRaysOnBoxEdges) {
  TriangleSoup soup;
  add_floor(soup);
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 4; ++k) {
      const glm::vec3 lo(-2.0f + float(i), 1.0f + 0.25f * float((i + k) % 2), -2.0f + float(k));
      add_box(soup, lo, lo + glm::vec3(0.5f), kWall);
    }
  const ReferenceScene scene(soup, test_materials());
  const RenderLight down = directional({0, -1, 0});
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 4; ++k) {
      const float x = -2.0f + float(i), z = -2.0f + float(k), y = 1.5f + 0.25f * float((i + k) % 2);
      // Corners, edge midpoints and the centre of the box's footprint.
      for (float dx : {0.0f, 0.25f, 0.5f})
        for (float dz : {0.0f, 0.25f, 0.5f}) {
          EXPECT_TRUE(near3(glm::vec3(0.0f), floor_transmittance(scene, down, x + dx, z + dz)))
              << "under box " << i << " " << k << " at " << dx << " " << dz;
          const SurfaceSample top = scene.intersect({x + dx, 5.0f, z + dz}, {0.0f, -1.0f, 0.0f});
          EXPECT_EQ(top.material, kWall);
          EXPECT_NEAR(position_of(top).y, y, kTol);
        }
      EXPECT_TRUE(near3(glm::vec3(1.0f), floor_transmittance(scene, down, x + 0.75f, z + 0.25f)));
    }
}

// A closed glass mesh crossed exactly through its vertices (every triangle of the fan reports the hit): the
// vertex counts once, so the transmittance there is continuous with that of a ray just beside it.
TEST(ReferenceShadow, ClosedMeshThroughVertices) {
  TriangleSoup soup;
  add_floor(soup);
  soup.append(make_uv_sphere(1.0f, 8, 12), glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 2.0f, 0.0f)),
              kGlass);
  const ReferenceScene scene(soup, test_materials());
  const RenderLight down = directional({0, -1, 0});
  int tested = 0;
  for (size_t v = 4; v < soup.positions.size(); ++v) {
    const glm::vec3 p(soup.positions[v]);
    if (p.x * p.x + p.z * p.z > 0.6f * 0.6f) continue;  // away from the silhouette, where the chord is steep
    const glm::vec3 exact = floor_transmittance(scene, down, p.x, p.z);
    const glm::vec3 beside = floor_transmittance(scene, down, p.x + 1e-3f, p.z + 7e-4f);
    EXPECT_LT(exact.x, 0.9f) << "under vertex " << v;
    EXPECT_TRUE(glm::all(glm::lessThan(glm::abs(exact - beside), glm::vec3(1e-2f)))) << "under vertex " << v;
    ++tested;
  }
  EXPECT_GT(tested, 10);
}

// (e) A point light: irradiance intensity / d^2, and the leaf's transmittance on the way; occluders beyond
// the light cast nothing, and a glass box beyond it (crossed twice) leaves the parity even.
TEST(ReferenceShadow, PointLightFalloffAndLeaf) {
  TriangleSoup soup;
  add_floor(soup);
  add_leaf(soup);
  add_box(soup, {-1.0f, 5.0f, -1.0f}, {1.0f, 5.5f, 1.0f}, kWall);
  add_box(soup, {-1.0f, 6.0f, -1.0f}, {1.0f, 7.0f, 1.0f}, kGlass);
  const ReferenceScene scene(soup, test_materials());
  const glm::vec3 intensity(16.0f, 32.0f, 8.0f);
  const RenderLight light = point_light({0.25f, 4.0f, 0.25f}, intensity);
  const SurfaceSample under = floor_sample(scene, 0.25f, 0.25f);  // under the diagonal, 4 below the light
  const LightAtPoint at = light_at(light, position_of(under));
  EXPECT_TRUE(near3(intensity / 16.0f, at.irradiance));
  EXPECT_TRUE(near3(glm::vec3(0, 1, 0), at.to_light));
  EXPECT_TRUE(near3(kLeafT, scene.transmittance(light, position_of(under), under.triangle)));
  // Off to the side, the slanted segment misses the leaf.
  EXPECT_TRUE(near3(glm::vec3(1.0f), floor_transmittance(scene, light, 2.5f, 0.25f)));
  // Slanted: from (-0.5, 0, -0.2) the segment meets y = 1 at (-0.3125, 1, -0.0875), inside the leaf.
  EXPECT_TRUE(near3(kLeafT, floor_transmittance(scene, light, -0.5f, -0.2f)));
}

// (f) intersect on a known triangle: position, barycentrics, distance in world units, normals facing the
// ray's origin from either side; misses and the (t_near, t_far) window.
TEST(ReferenceIntersect, KnownTriangle) {
  TriangleSoup soup;
  const uint32_t a = add_vertex(soup, {0, 1, 0}), b = add_vertex(soup, {2, 1, 0}),
                 c = add_vertex(soup, {0, 1, 2});
  soup.triangles.push_back({a, b, c, kWall});  // winding normal -y
  const ReferenceScene scene(soup, test_materials());
  const SurfaceSample above = scene.intersect({0.5f, 3.0f, 0.25f}, {0.0f, -2.0f, 0.0f});
  ASSERT_EQ(above.triangle, 0u);
  EXPECT_EQ(above.material, kWall);
  EXPECT_TRUE(near3(glm::vec3(0.5f, 1.0f, 0.25f), position_of(above)));
  EXPECT_NEAR(above.distance, 2.0f, kTol);
  EXPECT_NEAR(above.barycentric[0], 0.25f, kTol);   // weight of vertex 1: x / 2
  EXPECT_NEAR(above.barycentric[1], 0.125f, kTol);  // weight of vertex 2: z / 2
  EXPECT_TRUE(near3(glm::vec3(0, 1, 0), normal_of(above)));
  EXPECT_TRUE(near3(glm::vec3(0, 1, 0), geometric_of(above)));
  const SurfaceSample below = scene.intersect({0.5f, -1.0f, 0.25f}, {0.0f, 0.5f, 0.0f});
  ASSERT_EQ(below.triangle, 0u);
  EXPECT_NEAR(below.distance, 2.0f, kTol);
  EXPECT_TRUE(near3(glm::vec3(0, -1, 0), normal_of(below)));
  EXPECT_TRUE(near3(glm::vec3(0, -1, 0), geometric_of(below)));
  // t is in units of dir: the hit is at t = 1 for dir (0, -2, 0).
  EXPECT_EQ(scene.intersect({0.5f, 3.0f, 0.25f}, {0.0f, -2.0f, 0.0f}, 0.0f, 0.9f).triangle, VOXR_NO_TRIANGLE);
  EXPECT_EQ(scene.intersect({0.5f, 3.0f, 0.25f}, {0.0f, -2.0f, 0.0f}, 1.1f).triangle, VOXR_NO_TRIANGLE);
  const SurfaceSample miss = scene.intersect({1.5f, 3.0f, 1.5f}, {0.0f, -1.0f, 0.0f});
  EXPECT_EQ(miss.triangle, VOXR_NO_TRIANGLE);
  EXPECT_EQ(miss.distance, 0.0f);
  EXPECT_THROW(scene.intersect({0, 0, 0}, {0, 0, 0}), Error);
}

// A ridge along z at x = 0, y = 1, its faces down to y = 1 - slope at x = -1 (triangles 0, 1) and x = +1
// (triangles 2, 3).
TriangleSoup ridge(float slope) {
  TriangleSoup soup;
  const uint32_t r0 = add_vertex(soup, {0, 1, -1}), r1 = add_vertex(soup, {0, 1, 1});
  const uint32_t l0 = add_vertex(soup, {-1, 1 - slope, -1}), l1 = add_vertex(soup, {-1, 1 - slope, 1});
  const uint32_t q0 = add_vertex(soup, {1, 1 - slope, -1}), q1 = add_vertex(soup, {1, 1 - slope, 1});
  soup.triangles.push_back({l0, l1, r1, kWall});
  soup.triangles.push_back({l0, r1, r0, kWall});
  soup.triangles.push_back({r0, r1, q1, kWall});
  soup.triangles.push_back({r0, q1, q0, kWall});
  return soup;
}

// The crease rule: at a sharp ridge the interpolated normal would lean more than 45 degrees off the face, so
// the face's normal shades; on a gentle fold the interpolated normal is kept.
TEST(ReferenceIntersect, CreaseRule) {
  for (const float slope : {4.0f, 0.1f}) {  // ridge faces rising at about 76 and 6 degrees
    const TriangleSoup soup = ridge(slope);
    const ReferenceScene scene(soup, test_materials());
    const SurfaceSample s = scene.intersect({0.05f, 10.0f, 0.1f}, {0.0f, -1.0f, 0.0f});  // near the ridge
    ASSERT_NE(s.triangle, VOXR_NO_TRIANGLE);
    const float deviation = glm::degrees(std::acos(std::min(1.0f, glm::dot(normal_of(s), geometric_of(s)))));
    if (slope > 1.0f)
      EXPECT_TRUE(near3(geometric_of(s), normal_of(s)));
    else
      EXPECT_GT(deviation, 1.0f);
    EXPECT_GT(normal_of(s).y, 0.0f);
  }
}

// At a silhouette the shading normal can face away from a ray the geometric normal faces: it is turned by the
// geometric normal's flip and then replaced by it (the resolve's rule, raster_resolve.cl), never flipped on
// its own into the surface (issue 19: a "refracted" ray then left a glass surface while the path recorded it
// inside). A gentle fold (faces 35 degrees off level, so the ridge's vertex normals survive the crease rule)
// met near the ridge by a ray rising at 17 degrees towards it from the right: the front of the right face,
// whose shading normal (nearly +y there) points along the ray.
TEST(ReferenceIntersect, ShadingNormalFollowsTheGeometricNormalsSide) {
  const float slope = 0.7f;
  const TriangleSoup soup = ridge(slope);
  const ReferenceScene scene(soup, test_materials());
  const glm::vec3 d = glm::normalize(glm::vec3(-1.0f, 0.3f, 0.0f));
  const glm::vec3 hit(0.05f, 1.0f - slope * 0.05f, 0.1f);
  const SurfaceSample s = scene.intersect(hit - 2.0f * d, d);
  ASSERT_GE(s.triangle, 2u);  // the right face
  ASSERT_NE(s.triangle, VOXR_NO_TRIANGLE);
  EXPECT_LT(glm::dot(geometric_of(s), d), 0.0f);
  EXPECT_LE(glm::dot(normal_of(s), d), 0.0f);
  EXPECT_GT(glm::dot(normal_of(s), geometric_of(s)), 0.0f) << "the shading normal points into the surface";
  EXPECT_TRUE(near3(geometric_of(s), normal_of(s)));
}

// (g) A 32x24 render looking straight down: ambient where the rays miss, the hand-computed colour on a lit
// floor pixel, a leaf pixel, and the flat glass colour.
TEST(ReferenceRender, TinyScene) {
  TriangleSoup soup;
  add_floor(soup);
  add_leaf(soup);
  add_box(soup, {-2.5f, 0.5f, -0.5f}, {-1.5f, 1.0f, 0.5f}, kGlass);
  const std::vector<Material> materials = test_materials();
  const ReferenceScene scene(soup, materials);
  const glm::vec3 intensity(0.8f, 0.9f, 1.0f);
  const RenderLight light = directional({0, -1, 0}, intensity);
  CameraFrame camera;
  camera.eye = {0.0f, 5.0f, 0.0f};
  camera.forward = {0.0f, -1.0f, 0.0f};
  camera.right = {1.0f, 0.0f, 0.0f};
  camera.up = {0.0f, 0.0f, -1.0f};
  camera.tan_half_fov_y = 0.75f;  // at the floor: z in [-3.75, 3.75], x in [-5, 5]
  camera.width = 32;
  camera.height = 24;
  const ReferenceRender r = render_reference(scene, render_materials(materials), light, camera);
  ASSERT_EQ(r.image.width, 32u);
  ASSERT_EQ(r.image.height, 24u);
  ASSERT_EQ(r.samples.size(), 32u * 24u);
  ASSERT_EQ(r.transmittance.size(), 32u * 24u);
  const glm::vec3 ambient(0.1f);
  for (const glm::vec4& p : r.image.pixels) EXPECT_EQ(p.w, 1.0f);
  // Pixel x = 0 looks at x = -4.84 on the floor's plane: beyond the floor.
  EXPECT_EQ(r.samples[12 * 32 + 0].triangle, VOXR_NO_TRIANGLE);
  EXPECT_TRUE(near3(ambient, glm::vec3(r.image.at(0, 12))));
  EXPECT_TRUE(near3(ambient, glm::vec3(r.image.at(31, 0))));
  // Pixel (24, 12): floor at x = 2.66, z = 0.16, lit straight on: albedo * (ambient + E).
  const SurfaceSample& floor = r.samples[12 * 32 + 24];
  ASSERT_EQ(floor.material, kFloor);
  EXPECT_NEAR(floor.distance, glm::length(position_of(floor) - camera.eye), kTol);
  EXPECT_TRUE(near3(materials[kFloor].color * (ambient + intensity), glm::vec3(r.image.at(24, 12))));
  // Pixel (16, 12): the leaf, lit from above on the side the camera sees.
  ASSERT_EQ(r.samples[12 * 32 + 16].material, kLeaf);
  EXPECT_TRUE(near3(materials[kLeaf].color * (ambient + intensity), glm::vec3(r.image.at(16, 12))));
  // Pixel (7, 12): the glass box's top (x = -2.125, z = 0.125 at y = 1), flat: ambient * exp(-sigma_a).
  ASSERT_EQ(r.samples[12 * 32 + 7].material, kGlass);
  EXPECT_TRUE(near3(ambient * glm::exp(-kSigma), glm::vec3(r.image.at(7, 12))));
  // The image is the host shading of the samples and transmittance.
  const ImageRgba again =
      shade_samples(r.samples, r.transmittance, render_materials(materials), light, 32, 24);
  EXPECT_EQ(again.pixels, r.image.pixels);
  EXPECT_THROW(shade_samples(r.samples, r.transmittance, render_materials(materials), light, 32, 23), Error);
}

// The vector overload equals the single-point one at every sample, in order.
TEST(ReferenceShadow, VectorOverloadMatchesSingle) {
  TriangleSoup soup;
  add_floor(soup);
  add_leaf(soup);
  add_leaf(soup, 1.5f);
  add_box(soup, {0.8f, 0.5f, -1.0f}, {1.6f, 1.2f, 1.0f}, kGlass);
  add_box(soup, {-1.6f, 0.5f, -1.0f}, {-0.8f, 1.2f, 1.0f}, kWall);
  const ReferenceScene scene(soup, test_materials());
  const RenderLight light = directional({0.3f, -1.0f, 0.2f});
  std::vector<SurfaceSample> samples;
  for (int i = 0; i < 2000; ++i) {
    const float x = -2.9f + 5.8f * float(i % 50) / 49.0f, z = -2.9f + 5.8f * float(i / 50) / 39.0f;
    SurfaceSample none{};
    none.triangle = VOXR_NO_TRIANGLE;
    samples.push_back(i % 7 == 3 ? none : floor_sample(scene, x, z));
  }
  const std::vector<glm::vec3> all = reference_transmittance(scene, light, samples);
  ASSERT_EQ(all.size(), samples.size());
  int shadowed = 0;
  for (size_t i = 0; i < samples.size(); ++i) {
    const glm::vec3 one = samples[i].triangle == VOXR_NO_TRIANGLE
                              ? glm::vec3(1.0f)
                              : scene.transmittance(light, position_of(samples[i]), samples[i].triangle);
    EXPECT_EQ(one, all[i]) << i;
    shadowed += all[i].x < 1.0f;
  }
  EXPECT_GT(shadowed, 100);
}

TEST(ReferenceScene, RejectsBadMaterialIds) {
  TriangleSoup soup;
  add_floor(soup);
  soup.triangles[1].w = 7;
  EXPECT_THROW(ReferenceScene(soup, test_materials()), Error);
}

}  // namespace
}  // namespace voxr
