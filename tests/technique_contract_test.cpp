// The contract every registry row of the render seam (render/technique.h) keeps, parameterised over
// kShadowTechniques and kRefractionTechniques so a new row is tested by adding it:
//   shadows     transmittance 1 (to an ulp) where no caster stands between a lit receiver and the light,
//   exactly
//               0 (the row's documented answer) in the umbra of an opaque slab, finite images, device bytes
//               > 0 where the technique has a light-space structure;
//   refraction  identity paths and the primary samples as ends on a scene without dielectrics, finite images
//               and paths through a glass ball, device bytes > 0 where the technique has a structure.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "core/generators.h"
#include "reference/embree_reference.h"
#include "refraction_ball.h"
#include "render/frame_renderer.h"
#include "render/technique.h"
#include "test_support.h"

namespace voxr {
namespace {

namespace ball = test::ball;

// A directional light from the camera's side and to its left: a caster in front of the wall throws its
// shadow 1.25 to the right of itself (wall at z = -2.5, caster at z = 0..0.2).
RenderLight oblique_light() {
  RenderLight l{};
  l.directional = 1;
  const glm::vec3 d = glm::normalize(glm::vec3(0.5f, 0.0f, -1.0f));
  for (int a = 0; a < 3; ++a) {
    l.direction[a] = d[a];
    l.intensity[a] = 1.0f;
    l.ambient[a] = 0.2f;
  }
  return l;
}

std::vector<Material> opaque_materials() {
  Material wall;
  wall.name = "wall";
  wall.kind = MaterialKind::kOpaque;
  wall.color = glm::vec3(0.8f);
  return {wall};
}

constexpr uint32_t kWallTriangles = 12;  // the wall comes first in the soup

// An opaque wall facing the camera (z = -3..-2.5) and, with `caster`, an opaque slab in front of it.
TriangleSoup wall_scene(bool caster) {
  TriangleSoup soup;
  soup.append(make_box(glm::vec3(-4.0f, -4.0f, -3.0f), glm::vec3(4.0f, 4.0f, -2.5f)), glm::mat4(1.0f), 0);
  if (caster)
    soup.append(make_box(glm::vec3(-0.5f, -0.5f, 0.0f), glm::vec3(0.5f, 0.5f, 0.2f)), glm::mat4(1.0f), 0);
  return soup;
}

bool finite(const ImageRgba& image) {
  for (const glm::vec4& p : image.pixels)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !std::isfinite(p.w))
      return false;
  return true;
}

std::string row_name(const char* name) {
  std::string s = name;
  for (char& c : s)
    if (c == '-') c = '_';
  return s;
}

// One frame of `soup` with `options` (keep_samples), the reference given for the rows that ask it.
struct Rendered {
  RenderedFrame frame;
  uint64_t shadow_bytes = 0, refraction_bytes = 0;
};
Rendered render(const TriangleSoup& soup, const std::vector<Material>& materials, const RenderLight& light,
                RenderOptions options) {
  FrameRenderer renderer(test::runtime());
  EmbreeReference reference(soup, materials);
  options.keep_samples = true;
  renderer.prepare(options);
  renderer.set_scene(soup, materials, &reference);
  renderer.set_environment(EnvironmentMap::constant(glm::vec3(0.3f, 0.4f, 0.5f)));
  Rendered out;
  out.frame = renderer.render(light, ball::camera(), options);
  out.shadow_bytes = renderer.shadow_technique(options.shadows).device_bytes();
  out.refraction_bytes = renderer.refraction_technique(options.refraction.method).device_bytes();
  return out;
}

// ---- shadows ----

// Each row's transmittance in an opaque slab's umbra: 0, except none (every receiver lit). Uniform too: with
// only opaque casters its occupied voxels block (Eisemann & Decoret's opaque case; issue 20 kind 4).
float umbra_transmittance(ShadowMethod m) {
  return m == ShadowMethod::kNone ? 1.0f : 0.0f;
}
// The light-space grids and maps, and voxel-exact's triangle grid.
bool has_light_structure(ShadowMethod m) {
  return m == ShadowMethod::kVoxel || m == ShadowMethod::kUniform || m == ShadowMethod::kFilter ||
         m == ShadowMethod::kOpaque || m == ShadowMethod::kVoxelExact;
}

class ShadowContract : public ::testing::TestWithParam<ShadowTechniqueRow> {
 protected:
  RenderOptions options() const {
    RenderOptions o;
    o.shadows = GetParam().method;
    o.shadow_resolution = 64;
    o.refraction.method = RefractionMethod::kNone;
    return o;
  }
};

TEST_P(ShadowContract, NoCasterIsFullyLit) {
  const Rendered r = render(wall_scene(false), opaque_materials(), oblique_light(), options());
  EXPECT_TRUE(finite(r.frame.image));
  uint64_t receivers = 0;
  for (size_t i = 0; i < r.frame.samples.size(); ++i) {
    if (r.frame.samples[i].triangle == VOXR_NO_TRIANGLE) continue;
    ++receivers;
    // Exactly 1, but for the depth-map rows' percentage-closer weights, which sum to 1 in float to within an
    // ulp (0.99999994).
    for (int c = 0; c < 3; ++c) {
      ASSERT_LE(r.frame.transmittance[i][c], 1.0f) << "pixel " << i;
      ASSERT_GE(r.frame.transmittance[i][c], 1.0f - 1e-7f) << "pixel " << i;
    }
  }
  EXPECT_EQ(receivers, uint64_t(ball::kWidth) * ball::kHeight);  // the wall fills the view
  EXPECT_EQ(r.shadow_bytes > 0, has_light_structure(GetParam().method));
}

TEST_P(ShadowContract, OpaqueSlabBlocksItsUmbra) {
  const Rendered r = render(wall_scene(true), opaque_materials(), oblique_light(), options());
  EXPECT_TRUE(finite(r.frame.image));
  const float expected = umbra_transmittance(GetParam().method);
  uint64_t umbra = 0;
  for (size_t i = 0; i < r.frame.samples.size(); ++i) {
    const SurfaceSample& s = r.frame.samples[i];
    if (s.triangle >= kWallTriangles) continue;  // the caster, or nothing
    // The umbra is x in [0.75, 1.75], |y| <= 0.5 on the wall's face; its inner part:
    if (s.position[0] < 1.0f || s.position[0] > 1.5f || std::abs(s.position[1]) > 0.3f) continue;
    ++umbra;
    ASSERT_EQ(r.frame.transmittance[i], glm::vec3(expected)) << "pixel " << i;
  }
  EXPECT_GT(umbra, 20u);
}

INSTANTIATE_TEST_SUITE_P(EveryRow, ShadowContract, ::testing::ValuesIn(kShadowTechniques),
                         [](const ::testing::TestParamInfo<ShadowTechniqueRow>& p) {
                           return row_name(shadow_method_info(p.param.method).name);
                         });

// ---- refraction ----

bool has_refraction_structure(RefractionMethod m) {
  return m == RefractionMethod::kVoxelMulti || m == RefractionMethod::kVoxelTwo ||
         m == RefractionMethod::kVoxelExact || m == RefractionMethod::kImageSpace ||
         m == RefractionMethod::kDistanceMaps;
}

class RefractionContract : public ::testing::TestWithParam<RefractionTechniqueRow> {
 protected:
  RenderOptions options() const {
    RenderOptions o;
    // The references trace their own exact shadows; the device rows need none here.
    o.shadows = is_reference_refraction(GetParam().method) ? ShadowMethod::kReference : ShadowMethod::kNone;
    o.refraction.method = GetParam().method;
    o.refraction.resolution = 64;
    o.refraction.layer_res = 64;
    return o;
  }
};

TEST_P(RefractionContract, IdentityPathsAndUnchangedEndsWithoutDielectrics) {
  const TriangleSoup soup = wall_scene(true);
  RenderOptions none;
  none.shadows = ShadowMethod::kNone;
  none.refraction.method = RefractionMethod::kNone;
  const Rendered primary = render(soup, opaque_materials(), oblique_light(), none);
  const Rendered r = render(soup, opaque_materials(), oblique_light(), options());
  EXPECT_TRUE(finite(r.frame.image));
  ASSERT_EQ(r.frame.samples.size(), primary.frame.samples.size());
  ASSERT_EQ(r.frame.paths.size(), primary.frame.samples.size());
  const bool host = is_reference_refraction(GetParam().method);
  uint64_t same_triangle = 0;
  for (size_t i = 0; i < r.frame.paths.size(); ++i) {
    const RefractionPath& p = r.frame.paths[i];
    ASSERT_EQ(p.events, 0u) << "pixel " << i;
    ASSERT_EQ(p.fresnel, 0.0f) << "pixel " << i;
    ASSERT_EQ(glm::vec3(p.throughput[0], p.throughput[1], p.throughput[2]), glm::vec3(1.0f)) << "pixel " << i;
    const SurfaceSample &end = r.frame.samples[i], &first = primary.frame.samples[i];
    if (!host) {
      // The device rows hand on the primary samples themselves.
      ASSERT_EQ(std::memcmp(&end, &first, sizeof(SurfaceSample)), 0) << "pixel " << i;
    } else if (end.triangle == first.triangle) {
      // Embree's primary rays against the rasterizer's: the same surface point.
      ++same_triangle;
      for (int a = 0; a < 3; ++a) ASSERT_NEAR(end.position[a], first.position[a], 1e-4f) << "pixel " << i;
    }
  }
  // Pixel centres on a triangle edge may fall to either neighbour in the two; no more than 1 %.
  if (host) {
    EXPECT_GE(same_triangle, r.frame.paths.size() * 99 / 100);
  }
}

TEST_P(RefractionContract, GlassBallIsFiniteAndHasItsStructure) {
  const Rendered r = render(ball::scene(true), ball::materials(), ball::light(), options());
  EXPECT_TRUE(finite(r.frame.image));
  uint64_t refracted = 0;
  for (const RefractionPath& p : r.frame.paths) {
    for (int a = 0; a < 3; ++a) {
      ASSERT_TRUE(std::isfinite(p.throughput[a]));
      ASSERT_TRUE(std::isfinite(p.exit_direction[a]));
    }
    refracted += (p.events & VOXR_PATH_EVENTS_MASK) > 0;
  }
  if (GetParam().method != RefractionMethod::kNone) {
    EXPECT_GT(refracted, 100u);
  }
  EXPECT_EQ(r.refraction_bytes > 0, has_refraction_structure(GetParam().method));
}

INSTANTIATE_TEST_SUITE_P(EveryRow, RefractionContract, ::testing::ValuesIn(kRefractionTechniques),
                         [](const ::testing::TestParamInfo<RefractionTechniqueRow>& p) {
                           return row_name(refraction_method_info(p.param.method).name);
                         });

}  // namespace
}  // namespace voxr
