// The media stack (kernels/common/media_stack.h, docs/methods.md "The media stack"): media entered and
// left by the surfaces' winding, with a count per nested solid of one material, in the rule itself, the
// references' shadow rays, and every refraction method's picture of nested glass (issue 20, kind 2).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <string>

#include "cli_support.h"
#include "core/generators.h"
#include "core/material.h"
#include "core/triangle_soup.h"
#include "io/image_file.h"
#include "media_stack.h"
#include "metrics/image_metrics.h"
#include "reference/reference_refraction.h"
#include "reference/reference_scene.h"
#include "render/camera_frame.h"
#include "render/environment_map.h"
#include "render/render_scene.h"
#include "util/error.h"

namespace voxr {
namespace {

namespace fs = std::filesystem;
using test::run_voxr;
using test::scratch;

constexpr uint32_t kGlass = 0, kWater = 1, kOther = 2;

TEST(MediaStack, SameMaterialNestedCountsAndNeverBends) {
  VoxrMedia m = voxr_media_empty();
  // Into the outer solid (its winding normal faces the ray), then into the inner one of the same glass.
  ASSERT_TRUE(voxr_media_enters(&m, kGlass, -1.0f));
  EXPECT_EQ(voxr_media_far(&m, kGlass, 1), kGlass);
  voxr_media_cross(&m, kGlass, 1);
  ASSERT_TRUE(voxr_media_enters(&m, kGlass, -0.5f));
  EXPECT_EQ(voxr_media_far(&m, kGlass, 1), voxr_media_top(&m));  // n2 = n1: no bend, F = 0
  voxr_media_cross(&m, kGlass, 1);
  EXPECT_EQ(m.depth, 1u);
  EXPECT_EQ(m.count[0], 2u);
  // Out of the inner one: still in glass; out of the outer one: air.
  ASSERT_FALSE(voxr_media_enters(&m, kGlass, 0.5f));
  EXPECT_EQ(voxr_media_far(&m, kGlass, 0), kGlass);
  voxr_media_cross(&m, kGlass, 0);
  EXPECT_EQ(m.depth, 1u);
  EXPECT_EQ(m.count[0], 1u);
  ASSERT_FALSE(voxr_media_enters(&m, kGlass, 1.0f));
  EXPECT_EQ(voxr_media_far(&m, kGlass, 0), VOXR_MEDIA_AIR);
  voxr_media_cross(&m, kGlass, 0);
  EXPECT_EQ(m.depth, 0u);
  EXPECT_EQ(voxr_media_top(&m), VOXR_MEDIA_AIR);
}

TEST(MediaStack, DifferentMaterialsStackAndOverlapsKeepTheInnermost) {
  VoxrMedia m = voxr_media_empty();
  voxr_media_cross(&m, kGlass, 1);
  ASSERT_TRUE(voxr_media_enters(&m, kWater, -1.0f));
  EXPECT_EQ(voxr_media_far(&m, kWater, 1), kWater);  // glass to water: a real interface
  voxr_media_cross(&m, kWater, 1);
  ASSERT_EQ(m.depth, 2u);
  EXPECT_EQ(voxr_media_far(&m, kWater, 0), kGlass);  // water back to glass
  // Overlapping solids: leaving the outer glass while in the water keeps the water (n2 = n1).
  EXPECT_EQ(voxr_media_far(&m, kGlass, 0), kWater);
  voxr_media_cross(&m, kGlass, 0);
  ASSERT_EQ(m.depth, 1u);
  EXPECT_EQ(m.material[0], kWater);
  EXPECT_EQ(m.count[0], 1u);
}

TEST(MediaStack, LeavingAMaterialNotEnteredEntersIt) {
  // The fallback for open or inconsistently wound meshes: parity's choice, enter what the path is not in.
  VoxrMedia m = voxr_media_empty();
  EXPECT_TRUE(voxr_media_enters(&m, kGlass, 1.0f));
  EXPECT_TRUE(voxr_media_enters(&m, kGlass, 0.0f));
  voxr_media_cross(&m, kGlass, 1);
  EXPECT_TRUE(voxr_media_enters(&m, kWater, 1.0f));
  EXPECT_FALSE(voxr_media_enters(&m, kGlass, 1.0f));
  EXPECT_FALSE(voxr_media_enters(&m, kGlass, 0.0f));  // edge-on (a cancelled normal) inside: parity leaves
  EXPECT_FALSE(voxr_media_enters(&m, kGlass, NAN));
}

TEST(MediaStack, AFullStackOverflowsOnlyForANewEntry) {
  VoxrMedia m = voxr_media_empty();
  for (uint32_t k = 0; k < VOXR_MAX_MEDIA; ++k) {
    ASSERT_FALSE(voxr_media_overflows(&m, 10 + k, 1));
    voxr_media_cross(&m, 10 + k, 1);
  }
  EXPECT_TRUE(voxr_media_overflows(&m, kOther, 1));
  EXPECT_FALSE(voxr_media_overflows(&m, 10 + VOXR_MAX_MEDIA - 1, 1));  // the innermost again: a count
  EXPECT_FALSE(voxr_media_overflows(&m, kOther, 0));
}

// A shadow ray's ledger from the receiver (t = 0) towards a directional light (INFINITY).
float inside_length(std::initializer_list<std::pair<float, int>> crossings, float t_end = INFINITY) {
  VoxrSolidLedger l = voxr_ledger_make(kGlass);
  for (const auto& [t, enters] : crossings) voxr_ledger_cross(&l, t, enters, t < t_end ? 1 : 0);
  return voxr_ledger_inside_length(&l, t_end);
}

TEST(MediaStack, ShadowLedgerCountsNestedSolidsOfOneMaterial) {
  // Through a solid holding another of the same glass: inside from 1 to 4 (parity said 1-2 and 3-4).
  EXPECT_FLOAT_EQ(inside_length({{1.0f, 1}, {2.0f, 1}, {3.0f, 0}, {4.0f, 0}}), 3.0f);
  // A receiver inside the inner solid: inside to 2 (parity: even, so outside until 1, then 1-2).
  EXPECT_FLOAT_EQ(inside_length({{1.0f, 0}, {2.0f, 0}}), 2.0f);
  // One solid, and a point light at 2.5 inside it (the ray leaves at 3 beyond the light).
  EXPECT_FLOAT_EQ(inside_length({{1.0f, 1}, {3.0f, 0}}, 2.5f), 1.5f);
  // Two solids one behind the other.
  EXPECT_FLOAT_EQ(inside_length({{1.0f, 1}, {1.5f, 0}, {2.0f, 1}, {4.0f, 0}}), 2.5f);
}

TEST(MediaStack, ShadowLedgerFallsBackToParityWhereWindingDisagrees) {
  // An open sheet wound towards the light: the depth would be -1 at the receiver; parity (odd: inside).
  EXPECT_FLOAT_EQ(inside_length({{2.0f, 1}}), 2.0f);
  // An inside-out solid: depth -1 between its faces; parity as before.
  EXPECT_FLOAT_EQ(inside_length({{1.0f, 0}, {3.0f, 1}}), 2.0f);
}

// Two concentric spheres of material 0 at the origin, radius 0.6 holding radius 0.3.
TriangleSoup nested_spheres() {
  TriangleSoup soup;
  soup.append(make_uv_sphere(0.6f, 24, 48), glm::mat4(1.0f), 0);
  soup.append(make_uv_sphere(0.3f, 24, 48), glm::mat4(1.0f), 0);
  return soup;
}

TEST(MediaStack, ReferenceShadowThroughNestedGlassAbsorbsAlongTheWholeChord) {
  Material glass{.name = "glass",
                 .kind = MaterialKind::kDielectric,
                 .ior = 1.5f,
                 .absorption = glm::vec3(0.3f, 0.15f, 0.05f)};
  RenderLight light{};
  light.directional = 1u;
  light.direction[1] = -1.0f;  // straight down: the ray from under the centre goes up through both spheres
  const glm::vec3 under(0.0f, -1.0f, 0.0f);
  const float chord = 1.2f;  // through both poles of the outer sphere (parity gave 1.2 - 0.6)
  const ReferenceScene scene(nested_spheres(), {glass});
  const glm::vec3 t = scene.transmittance(light, under, VOXR_NO_TRIANGLE);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(t[c], std::exp(-glass.absorption[c] * chord), 1e-4f) << c;
}

TEST(MediaStack, AnInwardSphereIsACavityInTheReferenceShadow) {
  const nlohmann::json inward = {{"radius", 0.3}, {"stacks", 24}, {"slices", 48}, {"inward", true}};
  TriangleSoup soup;
  soup.append(make_uv_sphere(0.6f, 24, 48), glm::mat4(1.0f), 0);
  soup.append(make_generated("sphere", inward, "test", "params"), glm::mat4(1.0f), 0);
  const Material glass{.name = "glass",
                       .kind = MaterialKind::kDielectric,
                       .ior = 1.5f,
                       .absorption = glm::vec3(0.3f, 0.15f, 0.05f)};
  RenderLight light{};
  light.directional = 1u;
  light.direction[1] = -1.0f;
  const ReferenceScene scene(soup, {glass});
  const glm::vec3 t = scene.transmittance(light, glm::vec3(0.0f, -1.0f, 0.0f), VOXR_NO_TRIANGLE);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(t[c], std::exp(-glass.absorption[c] * 0.6f), 1e-4f) << c;
  EXPECT_THROW(make_generated("sphere", {{"inward", 1}}, "test", "params"), Error);
}

// The matched reference's path of one ray through two concentric spheres (radius 0.6 of glass, 0.3 of index
// `inner_ior`), 0.11 off their centre: the interfaces it counts and where it leaves.
RefractionPath path_through_nested(float inner_ior, bool inner) {
  TriangleSoup soup;
  soup.append(make_uv_sphere(0.6f, 24, 48), glm::mat4(1.0f), 0);
  if (inner) soup.append(make_uv_sphere(0.3f, 24, 48), glm::mat4(1.0f), inner_ior == 1.5f ? 0 : 1);
  const glm::vec3 sigma(0.3f, 0.15f, 0.05f);
  const std::vector<Material> materials{
      {.name = "glass", .kind = MaterialKind::kDielectric, .ior = 1.5f, .absorption = sigma},
      {.name = "core", .kind = MaterialKind::kDielectric, .ior = inner_ior, .absorption = sigma}};
  const ReferenceScene scene(soup, materials);
  CameraFrame camera;
  camera.eye = glm::vec3(0.1f, 0.05f, 3.0f);
  camera.forward = glm::vec3(0.0f, 0.0f, -1.0f);
  camera.right = glm::vec3(1.0f, 0.0f, 0.0f);
  camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
  camera.tan_half_fov_y = 0.01f;
  camera.width = camera.height = 1;
  RenderLight light{};
  light.directional = 1u;
  light.direction[1] = -1.0f;
  return render_refraction_reference(scene, render_materials(materials), light, EnvironmentMap::checker(16),
                                     camera, ReferenceModel::kMatched)
      .paths[0];
}

TEST(MediaStack, ReferencePathCountsOnlyRealInterfaces) {
  const RefractionPath single = path_through_nested(1.5f, false);
  const RefractionPath same = path_through_nested(1.5f, true);
  const RefractionPath dense = path_through_nested(1.8f, true);
  EXPECT_EQ(single.events, 2u | VOXR_PATH_ENV);
  EXPECT_EQ(same.events, 2u | VOXR_PATH_ENV);   // the inner sphere of the same glass is no interface
  EXPECT_EQ(dense.events, 4u | VOXR_PATH_ENV);  // 1.5 to 1.8 and back: two more refractions
  for (int c = 0; c < 3; ++c) {
    EXPECT_FLOAT_EQ(same.exit_direction[c], single.exit_direction[c]) << c;
    EXPECT_NEAR(same.throughput[c], single.throughput[c], 1e-6f) << c;
  }
  const glm::vec3 a(single.exit_direction[0], single.exit_direction[1], single.exit_direction[2]);
  const glm::vec3 b(dense.exit_direction[0], dense.exit_direction[1], dense.exit_direction[2]);
  EXPECT_GT(std::acos(std::min(1.0f, glm::dot(a, b))), 0.01f);  // the core bends the ray (radians)
}

// The r02 scenes of issue 20: a glass sphere r 0.6 over a floor, alone or holding a sphere r 0.3 of glass
// of index `inner_ior` (the same material when 1.5).
fs::path write_scene(const std::string& name, double inner_ior, bool inner) {
  const std::string glass =
      R"({"name": "glass", "kind": "dielectric", "ior": 1.5, "absorption": [0.3, 0.15, 0.05]})";
  const std::string core = R"(, {"name": "core", "kind": "dielectric", "ior": )" + std::to_string(inner_ior) +
                           R"(, "absorption": [0.3, 0.15, 0.05]})";
  const bool same = inner_ior == 1.5;
  std::string meshes =
      R"([{"generator": "plane", "params": {"size": [6, 6]}, "material": "floor"},
          {"generator": "sphere", "params": {"radius": 0.6, "stacks": 24, "slices": 48}, "material": "glass",
           "transform": {"translate": [0, 0.65, 0]}})";
  if (inner)
    meshes += R"(, {"generator": "sphere", "params": {"radius": 0.3, "stacks": 24, "slices": 48},
                   "material": ")" +
              std::string(same ? "glass" : "core") + R"(", "transform": {"translate": [0, 0.65, 0]}})";
  meshes += "]";
  return test::write_scratch_file(name,
                                  R"({"materials": [)" + glass + (same ? "" : core) +
                                      R"(, {"name": "floor", "kind": "opaque", "color": [0.7, 0.7, 0.65]}],
                "meshes": )" + meshes +
                                      R"(,
                "light": {"type": "directional", "direction": [-0.4, -1, -0.5], "intensity": [0.9, 0.9, 0.9]},
                "camera": {"position": [0, 1.6, 3.2], "look_at": [0, 0.5, 0], "fov_deg": 45, "width": 160,
                           "height": 120},
                "environment": {"procedural": "checker"}})");
}

ImageRgba render(const fs::path& scene, const std::string& options, const std::string& name) {
  const fs::path out = scratch() / (name + ".exr");
  const test::CliResult r = run_voxr("render " + scene.string() + " " + options + " -o " + out.string());
  EXPECT_EQ(r.code, 0) << options << ": " << r.err;
  return read_image(out.string());
}

struct Method {
  std::string name, options;
  bool exact;  // traces the exact triangles (the references, voxel-exact)
};

const Method kMethods[] = {
    {"reference", "--refraction reference --shadows reference", true},
    {"reference-full", "--refraction reference-full --shadows reference", true},
    {"voxel-exact", "--refraction voxel-exact --shadows voxel-exact", true},
    {"voxel-multi", "--refraction voxel-multi --shadows voxel-exact", false},
    {"voxel-two", "--refraction voxel-two --shadows voxel-exact", false},
    {"distance-maps", "--refraction distance-maps --shadows voxel-exact", false},
};

// Within noise: the exact methods trace the same rays through an interface that does not bend, so their
// pictures differ by the rounding of the absorption alone (RMSE <= 1e-3; measured 4e-7); the voxel and map
// methods by no more than their own error against the matched reference on the single sphere, the noise
// floor measured here (at 160x120: voxel-multi 0.037, voxel-two 0.036, distance-maps 0.010; nested vs
// single measured 0.023, 0.016, 0.0025). The fault rendered the core as an air bubble: RMSE 0.076.
TEST(MediaStack, NestedSameGlassRendersAsTheOuterSphereInEveryMethod) {
  const fs::path nested = write_scene("nested-same.json", 1.5, true);
  const fs::path single = write_scene("single-outer.json", 1.5, false);
  const ImageRgba truth = render(single, "--refraction reference --shadows reference", "single-truth");
  for (const Method& m : kMethods) {
    const ImageRgba a = render(nested, m.options, "nested-" + m.name);
    const ImageRgba b = render(single, m.options, "single-" + m.name);
    const double e = rmse(a, b), bound = m.exact ? 1e-3 : rmse(b, truth);
    EXPECT_LE(e, bound) << m.name;
    std::cout << "[ nested same glass vs single ] " << m.name << " RMSE " << e << " (bound " << bound
              << ")\n";
  }
}

TEST(MediaStack, NestedDifferentGlassStillBendsAtTheInnerSurface) {
  const fs::path nested = write_scene("nested-dense.json", 1.8, true);
  const fs::path single = write_scene("single-outer-2.json", 1.5, false);
  const ImageRgba truth = render(nested, "--refraction reference --shadows reference", "dense-truth");
  for (const Method& m : kMethods) {
    if (m.name == "voxel-two") continue;  // by design refracts at its front object's two surfaces only
    const ImageRgba a = render(nested, m.options, "dense-" + m.name);
    const ImageRgba b = render(single, m.options, "single2-" + m.name);
    const double e = rmse(a, b);
    EXPECT_GE(e, 0.02) << m.name;
    // Not just different: voxel-exact is the matched reference's picture (issue 19's requirement, RMSE
    // <= 0.01), so the inner surface bends where the reference bends it.
    if (m.name == "voxel-exact") EXPECT_LE(rmse(a, truth), 0.01) << m.name;
    std::cout << "[ nested 1.8 glass vs single ] " << m.name << " RMSE " << e << "\n";
  }
}

TEST(MediaStack, ShadowsUnderNestedSameGlassAreTheOuterSpheresShadows) {
  // Refraction off (dielectrics shaded flat, alike in both scenes): the floor's shadow alone differs, and
  // by winding the inner sphere's space absorbs too (by parity it did not: a lighter core in the shadow).
  const fs::path nested = write_scene("nested-shadow.json", 1.5, true);
  const fs::path single = write_scene("single-shadow.json", 1.5, false);
  for (const std::string shadows : {"reference", "voxel-exact"}) {
    const std::string options = "--refraction none --shadows " + shadows;
    const double e = rmse(render(nested, options, "shadow-nested-" + shadows),
                          render(single, options, "shadow-single-" + shadows));
    EXPECT_LE(e, 1e-4) << shadows;
  }
}

}  // namespace
}  // namespace voxr
