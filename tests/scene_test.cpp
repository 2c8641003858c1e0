// Scene files: every section, the error for every kind of mistake, transforms, defaults, the built-in scene.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "core/default_scene.h"
#include "core/generators.h"
#include "core/mesh_topology.h"
#include "core/scene.h"
#include "test_support.h"
#include "util/error.h"

namespace voxr {
namespace {

namespace fs = std::filesystem;

const char* kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

std::string scene_error(const std::string& text) {
  try {
    parse_scene(text, "s.json", ".");
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

void expect_near(glm::vec3 a, glm::vec3 b, float tolerance = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(Scene, LoadsEverySection) {
  test::TempDir dir;
  dir.write("meshes/tri.obj", kTriangleObj);
  const fs::path file = dir.write("scenes/s.json", R"({
    // comments are allowed
    "materials": [
      {"name": "glass", "kind": "dielectric", "ior": 1.33, "absorption": [0.1, 0.2, 0.3]},
      {"name": "floor", "kind": "opaque", "color": [0.1, 0.2, 0.3]},
      {"name": "leaf", "kind": "sheet", "transmittance": [0.5, 0.8, 0.4]}
    ],
    "meshes": [
      {"file": "../meshes/tri.obj", "material": "floor", "subdivide": 1,
       "transform": {"scale": 2, "translate": [1, 2, 3]}},
      {"generator": "torus", "params": {"major": 1, "minor": 0.4}, "material": "glass"},
      {"generator": "tree", "params": {"density": 0.1}, "material": ["floor", "leaf"]}
    ],
    "light": {"type": "directional", "direction": [0, -2, 0], "intensity": [2, 2, 2]},
    "camera": {"position": [0, 1, 5], "look_at": [0, 0, 0], "fov_deg": 30, "width": 640, "height": 480},
    "environment": {"color": [0.1, 0.1, 0.2]},
    "grid": {"dims": [64, 32, 16], "bounds": [-2, -2, -2, 2, 2, 2], "margin_voxels": 1}
  })");
  const Scene s = load_scene(file);
  EXPECT_EQ(s.source, file.string());
  ASSERT_EQ(s.materials.size(), 3u);
  EXPECT_EQ(s.materials[0].kind, MaterialKind::kDielectric);
  EXPECT_FLOAT_EQ(s.materials[0].ior, 1.33f);
  EXPECT_EQ(s.materials[0].absorption, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(s.materials[1].kind, MaterialKind::kOpaque);
  EXPECT_EQ(s.materials[1].color, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(s.materials[2].kind, MaterialKind::kSheet);
  EXPECT_EQ(s.materials[2].transmittance, glm::vec3(0.5f, 0.8f, 0.4f));

  ASSERT_EQ(s.meshes.size(), 3u);
  EXPECT_EQ(fs::canonical(s.meshes[0].source), fs::canonical(dir.path() / "meshes/tri.obj"));
  EXPECT_EQ(s.meshes[0].soup.triangle_count(), 4u);  // subdivided once, in object space
  EXPECT_EQ(s.meshes[0].material, 1u);
  expect_near(glm::vec3(s.meshes[0].transform * glm::vec4(1, 0, 0, 1)), glm::vec3(3, 2, 3));
  EXPECT_EQ(s.meshes[1].source, "generator:torus");
  EXPECT_EQ(s.meshes[1].soup.triangle_count(), 800u);
  EXPECT_EQ(s.meshes[1].material, 0u);
  EXPECT_EQ(s.meshes[2].material, TriangleSoup::kKeepMaterial);

  EXPECT_EQ(s.light.type, "directional");
  EXPECT_EQ(s.light.direction, glm::vec3(0, -1, 0));
  EXPECT_EQ(s.light.intensity, glm::vec3(2.0f));
  EXPECT_EQ(s.camera.position, glm::dvec3(0, 1, 5));
  EXPECT_EQ(s.camera.up, glm::vec3(0, 1, 0));
  EXPECT_EQ(s.camera.fov_deg, 30.0f);
  EXPECT_EQ(s.camera.width, 640u);
  EXPECT_EQ(s.camera.height, 480u);
  EXPECT_EQ(s.environment.color, glm::vec3(0.1f, 0.1f, 0.2f));
  EXPECT_TRUE(s.grid_given);
  ASSERT_TRUE(s.grid.dims.has_value());
  EXPECT_EQ(*s.grid.dims, glm::uvec3(64, 32, 16));
  ASSERT_TRUE(s.grid.bounds.has_value());
  EXPECT_EQ(s.grid.bounds->lo, glm::dvec3(-2.0));
  EXPECT_EQ(s.grid.margin_voxels, 1.0f);

  const TriangleSoup world = scene_triangles(s);
  const TriangleSoup tree = make_tree(0.1f, 1);
  EXPECT_EQ(world.triangle_count(), 4u + 800u + tree.triangle_count());
  for (size_t t = 0; t < 4; ++t) EXPECT_EQ(world.triangles[t].w, 1u);
  for (size_t t = 4; t < 804; ++t) EXPECT_EQ(world.triangles[t].w, 0u);
  // Tree: trunk (id 0) -> "floor" (1), leaves (id 1) -> "leaf" (2).
  for (size_t t = 0; t < tree.triangle_count(); ++t)
    EXPECT_EQ(world.triangles[804 + t].w, tree.triangles[t].w == kTreeLeafMaterial ? 2u : 1u);
}

TEST(Scene, UnknownKeysNameTheirPath) {
  EXPECT_EQ(scene_error(R"({"meshes": [{"generator": "box"}, {"generator": "box", "materail": "x"}]})"),
            "s.json: unknown key 'meshes[1].materail' (did you mean 'meshes[1].material'?)");
  EXPECT_EQ(scene_error(R"({"meshes": [{"generator": "box"}], "lights": {}})"),
            "s.json: unknown key 'lights' (did you mean 'light'?)");
  EXPECT_EQ(
      scene_error(R"({"meshes": [{"generator": "box"}], "camera": {"zoom": 2}})"),
      "s.json: unknown key 'camera.zoom' (allowed here: position, look_at, up, fov_deg, width, height)");
  EXPECT_EQ(
      scene_error(R"({"meshes": [{"generator": "box", "transform": {"rotate": [0, 0, 0]}}]})"),
      "s.json: unknown key 'meshes[0].transform.rotate' (did you mean 'meshes[0].transform.rotate_deg'?)");
  EXPECT_EQ(scene_error(R"({"meshes": [{"generator": "box", "params": {"size": 1}}]})"),
            "s.json: unknown key 'meshes[0].params.size' (allowed here: lo, hi)");
}

TEST(Scene, BadValuesNameTheirKey) {
  const std::string box = R"("meshes": [{"generator": "box"}])";
  const std::pair<std::string, std::string> cases[] = {
      {R"({"materials": [{"name": "g", "kind": "dielectric", "ior": -1.5}], )" + box + "}",
       "s.json: 'materials[0].ior' must be positive (got -1.5)"},
      {R"({"materials": [{"name": "g", "kind": "metal"}], )" + box + "}",
       "s.json: 'materials[0].kind' must be opaque, dielectric or sheet (got \"metal\")"},
      {R"({"materials": [{"name": "g", "kind": "opaque", "ior": 1.5}], )" + box + "}",
       "s.json: 'materials[0].ior' is not used by kind 'opaque'"},
      {R"({"materials": [{"kind": "opaque"}], )" + box + "}",
       "s.json: missing required key 'materials[0].name'"},
      {R"({"materials": [{"name": "a", "kind": "opaque"}, {"name": "a", "kind": "sheet"}], )" + box + "}",
       "s.json: 'materials[1].name' repeats the material name \"a\""},
      {R"({"materials": [{"name": "s", "kind": "sheet", "transmittance": [0.5, 1.5, 0]}], )" + box + "}",
       "s.json: 'materials[0].transmittance' must have every component in [0, 1] (got [0.5,1.5,0])"},
      {R"({"materials": [{"name": "a", "kind": "opaque"}], "meshes": [{"generator": "box", "material": "b"}]})",
       "s.json: 'meshes[0].material' names no material: \"b\" (materials: a)"},
      {R"({"materials": [{"name": "a", "kind": "opaque"}], "meshes": [{"generator": "tree", "material": ["a"]}]})",
       "s.json: 'meshes[0].material' must list a material for each of the material ids 0..1 that "
       "generator:tree "
       "carries (got [\"a\"])"},
      {R"({"materials": []})", "s.json: 'materials' must be a non-empty array of materials (got [])"},
      {R"({})", "s.json: missing required key 'meshes'"},
      {R"({"meshes": {}})", "s.json: 'meshes' must be a non-empty array of meshes (got {})"},
      {R"({"meshes": [{"material": "default"}]})",
       "s.json: 'meshes[0]' needs exactly one of 'file' and 'generator'"},
      {R"({"meshes": [{"generator": "cube"}]})",
       "s.json: 'meshes[0].generator' must be one of torus, sphere, box, vase, tree, plane, foliage (got "
       "\"cube\")"},
      {R"({"meshes": [{"generator": "torus", "params": {"rings": 2}}]})",
       "s.json: 'meshes[0].params.rings' must be an integer in [3, 4096] (got 2)"},
      {R"({"meshes": [{"generator": "box", "subdivide": 9}]})",
       "s.json: 'meshes[0].subdivide' must be an integer in [0, 8] (got 9)"},
      {R"({"meshes": [{"generator": "box", "transform": {"translate": [1, 2]}}]})",
       "s.json: 'meshes[0].transform.translate' must be an array of 3 numbers (got [1,2])"},
      {R"({"meshes": [{"generator": "box", "transform": {"scale": [1, 0, 1]}}]})",
       "s.json: 'meshes[0].transform.scale' must not be 0 along any axis (got [1,0,1])"},
      {R"({"meshes": [{"generator": "box", "transform": {"scale": "big"}}]})",
       "s.json: 'meshes[0].transform.scale' must be a number or an array of 3 numbers (got \"big\")"},
      {R"({"meshes": [{"file": "nowhere.obj"}]})", "s.json: 'meshes[0].file' 'nowhere.obj' not found in"},
      {"{" + box + R"(, "light": {"type": "spot"}})",
       "s.json: 'light.type' must be point or directional (got \"spot\")"},
      {"{" + box + R"(, "light": {"type": "point"}})", "s.json: missing required key 'light.position'"},
      {"{" + box + R"(, "light": {"type": "directional", "direction": [0, 0, 0]}})",
       "s.json: 'light.direction' must not be zero (got [0,0,0])"},
      {"{" + box + R"(, "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "fov_deg": 180}})",
       "s.json: 'camera.fov_deg' must be in (0, 180) (got 180)"},
      {"{" + box + R"(, "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "up": [0, 0, 1]}})",
       "s.json: 'camera.up' must be non-zero and not parallel to the view direction (got [0,0,1])"},
      {"{" + box + R"(, "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "width": 0}})",
       "s.json: 'camera.width' must be an integer in [1, 16384] (got 0)"},
      {"{" + box + R"(, "environment": {"color": [0.5, 0.5]}})",
       "s.json: 'environment.color' must be an array of 3 numbers (got [0.5,0.5])"},
      {"{" + box + R"(, "environment": {"procedural": "stars"}})",
       "s.json: 'environment.procedural' must be \"checker\" (got \"stars\")"},
      {"{" + box + R"(, "environment": {"color": [1, 1, 1], "procedural": "checker"}})",
       "s.json: 'environment' needs exactly one of 'color', 'image' and 'procedural'"},
      {"{" + box + R"(, "environment": {"imag": "sky.exr"}})",
       "s.json: unknown key 'environment.imag' (did you mean 'environment.image'?)"},
      {"{" + box + R"(, "grid": {"res": 64, "dims": [1, 2, 3]}})",
       "s.json: 'grid' takes 'res' or 'dims', not both"},
      {"{" + box + R"(, "grid": {"dims": [1, 0, 3]}})",
       "s.json: 'grid.dims' must hold integers in [1, 16384] (got [1,0,3])"},
      {"{" + box + R"(, "grid": {"bounds": [0, 0, 0, 1, -1, 1]}})",
       "s.json: 'grid.bounds' must have x0 < x1, y0 < y1 and z0 < z1 (got [0,0,0,1,-1,1])"},
      {"[1, 2]", "s.json: 'the top level' must be an object (got [1,2])"},
  };
  for (const auto& [text, expected] : cases) {
    const std::string message = scene_error(text);
    EXPECT_EQ(message.substr(0, expected.size()), expected) << text;
  }
}

// A value quoted in a message is bounded in depth and length (issue 20, kind 1: dumping a 100 000-deep array
// whole overflowed the stack): the message names the file and the key and shows a few levels.
TEST(Scene, DeepAndHugeValuesAreQuotedBriefly) {
  const std::string box = R"("meshes": [{"generator": "box"}])";
  const int depth = 100000;
  const std::string deep = std::string(depth, '[') + "1" + std::string(depth, ']');
  try {
    parse_scene("{" + box + R"(, "camera": {"position": )" + deep + "}}", "deep.json", ".");
    FAIL() << "a 100 000-deep position was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "deep.json: 'camera.position' must be an array of 3 numbers (got [[[[[...]]]]])");
  }
  std::string wide = "[0";
  for (int i = 1; i < 200000; ++i) wide += ",0";
  wide += "]";
  try {
    parse_scene("{" + box + R"(, "camera": {"position": )" + wide + "}}", "wide.json", ".");
    FAIL() << "a 200 000-element position was accepted";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("wide.json: 'camera.position'"), std::string::npos) << what;
    EXPECT_LT(what.size(), 160u) << what;
  }
}

TEST(Scene, SyntaxErrorsGiveTheLine) {
  EXPECT_EQ(scene_error("{\n  \"meshes\": [\n    {\"generator\": \"box\",}\n  ]\n}"),
            "s.json: JSON parse error at line 3, column 25: syntax error while parsing object key - "
            "unexpected '}'; "
            "expected string literal");
  EXPECT_EQ(scene_error(R"({"meshes": [{"generator": "box"}], "camera": {"fov_deg": 30, "fov_deg": 40}})"),
            "s.json: duplicate key 'camera.fov_deg'");
  EXPECT_EQ(scene_error(
                R"({"meshes": [{"generator": "box"}, {"generator": "box", "material": 1, "material": 2}]})"),
            "s.json: duplicate key 'meshes[1].material'");
}

TEST(Scene, MeshErrorsNameTheMeshKey) {
  test::TempDir dir;
  dir.write("broken.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
  const fs::path file = dir.write("s.json", R"({"meshes": [{"generator": "box"}, {"file": "broken.obj"}]})");
  try {
    load_scene(file);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              fmt::format("{}: 'meshes[1].file' could not be loaded: {}: line 2: vertex "
                          "coordinate 'nan' is not a finite number (of magnitude at most 1e+30)",
                          file.string(), (dir.path() / "broken.obj").string()));
  }
  EXPECT_THROW(load_scene(dir.path() / "absent.json"), Error);
}

TEST(Scene, TransformScalesThenRotatesXYZThenTranslates) {
  // Rotations about X then Y: (0,1,0) -> X90 -> (0,0,1) -> Y90 -> (1,0,0). The other order gives (0,0,1).
  expect_near(
      glm::vec3(make_transform(glm::vec3(1), glm::vec3(90, 90, 0), glm::vec3(0)) * glm::vec4(0, 1, 0, 1)),
      glm::vec3(1, 0, 0));
  // Y then Z: (1,0,0) -> Y90 -> (0,0,-1) -> Z90 -> (0,0,-1); (0,0,1) -> Y90 -> (1,0,0) -> Z90 -> (0,1,0).
  expect_near(
      glm::vec3(make_transform(glm::vec3(1), glm::vec3(0, 90, 90), glm::vec3(0)) * glm::vec4(0, 0, 1, 1)),
      glm::vec3(0, 1, 0));
  // Scale before rotating: (1,0,0) -> scale x2 -> (2,0,0) -> Z90 -> (0,2,0) -> translate -> (10,2,0).
  expect_near(glm::vec3(make_transform(glm::vec3(2, 1, 1), glm::vec3(0, 0, 90), glm::vec3(10, 0, 0)) *
                        glm::vec4(1, 0, 0, 1)),
              glm::vec3(10, 2, 0));

  const Scene s =
      parse_scene(R"({"meshes": [{"generator": "box", "params": {"lo": [0, 0, 0], "hi": [1, 1, 1]},
      "transform": {"scale": [2, 1, 1], "rotate_deg": [0, 0, 90], "translate": [10, 0, 0]}}]})",
                  "s.json", ".");
  const TriangleSoup world = scene_triangles(s);
  // Box corner 1 is (1,0,0); positions are relative to the scene's anchor.
  expect_near(glm::vec3(world.anchor + glm::dvec3(glm::vec3(world.positions[1]))), glm::vec3(10, 2, 0));
  EXPECT_NEAR(signed_volume(world), 2.0, 1e-5);
}

TEST(Scene, MirroringKeepsNormalsOutward) {
  const Scene s = parse_scene(R"({"meshes": [{"generator": "torus", "transform": {"scale": [-1, 2, 1]}}]})",
                              "s.json", ".");
  const TriangleSoup world = scene_triangles(s);
  EXPECT_NEAR(signed_volume(world) / (2.0 * signed_volume(s.meshes[0].soup)), 1.0, 1e-5);
}

TEST(Scene, DefaultsFrameTheScene) {
  const Scene s = parse_scene(
      R"({"meshes": [{"generator": "box", "params": {"lo": [0, 0, 0], "hi": [4, 2, 2]}}]})", "s.json", ".");
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].name, "default");
  EXPECT_EQ(s.materials[0].kind, MaterialKind::kOpaque);
  EXPECT_FALSE(s.grid_given);
  EXPECT_EQ(s.environment.color, kDefaultEnvironment);
  const glm::vec3 center(2, 1, 1);
  expect_near(s.camera.look_at, center);
  EXPECT_GT(s.camera.position.z, 3.0f);  // in front (+Z)
  EXPECT_FLOAT_EQ(s.camera.fov_deg, 45.0f);
  // Every corner of the bounds lies inside the vertical field of view.
  const glm::vec3 view = glm::normalize(s.camera.look_at - s.camera.position);
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner(i & 1 ? 4 : 0, i & 2 ? 2 : 0, i & 4 ? 2 : 0);
    const float angle =
        glm::degrees(std::acos(glm::dot(view, glm::normalize(corner - glm::vec3(s.camera.position)))));
    EXPECT_LT(angle, 22.5f);
  }
  EXPECT_EQ(s.light.type, "point");
  EXPECT_GT(s.light.position.y, 2.0f);  // above
  EXPECT_GT(s.light.position.z, 2.0f);  // in front
  const glm::vec3 d = glm::vec3(s.light.position) - center;
  EXPECT_NEAR(s.light.intensity.x / glm::dot(d, d), 1.0f, 1e-5f);
}

TEST(Scene, LoadInputWrapsAMeshFile) {
  test::TempDir dir;
  const fs::path mesh = dir.write("tri.obj", kTriangleObj);
  const Scene s = load_input(mesh);
  EXPECT_EQ(s.source, mesh.string());
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].name, "default");
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].transform, glm::mat4(1.0f));
  // The mesh keeps its own material ids; each names a scene material (one here: the file has none).
  EXPECT_EQ(s.meshes[0].material, TriangleSoup::kKeepMaterial);
  EXPECT_EQ(scene_triangles(s).triangle_count(), 1u);
  const Scene two = load_input(dir.write("two.obj",
                                         "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nusemtl a\nf 1 2 3\n"
                                         "usemtl b\nf 1 2 4\n"));
  ASSERT_EQ(two.materials.size(), 2u);
  EXPECT_EQ(two.materials[1].kind, MaterialKind::kOpaque);
  const TriangleSoup soup = scene_triangles(two);
  ASSERT_EQ(soup.triangle_count(), 2u);
  EXPECT_EQ(soup.triangles[0].w, 0u);
  EXPECT_EQ(soup.triangles[1].w, 1u);
  expect_near(s.camera.look_at, glm::vec3(0.5f, 0.5f, 0.0f));
  // .json goes to the scene loader.
  const fs::path scene = dir.write("s.json", R"({"meshes": [{"file": "tri.obj", "subdivide": 2}]})");
  EXPECT_EQ(scene_triangles(load_input(scene)).triangle_count(), 16u);
  EXPECT_THROW(load_input(dir.path() / "tri.3ds"), Error);
}

TEST(Scene, MeshDirResolvesSharedMeshes) {
  test::TempDir meshes, scenes;
  meshes.write("shared.obj", kTriangleObj);
  scenes.write("local.obj", kTriangleObj);
  const test::ScopedEnv env("VOXR_MESH_DIR", meshes.path().string());
  const fs::path file = scenes.write("s.json", R"({"meshes": [{"file": "$VOXR_MESH_DIR/shared.obj"},
      {"file": "shared.obj"}, {"file": "local.obj"}]})");
  const Scene s = load_scene(file);
  EXPECT_EQ(fs::path(s.meshes[0].source), meshes.path() / "shared.obj");
  EXPECT_EQ(fs::path(s.meshes[1].source), meshes.path() / "shared.obj");
  EXPECT_EQ(fs::path(s.meshes[2].source), scenes.path() / "local.obj");
  const fs::path bad = scenes.write("bad.json", R"({"meshes": [{"file": "$VOXR_MESH_DIR/none.obj"}]})");
  try {
    load_scene(bad);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'meshes[0].file' names '" + (meshes.path() / "none.obj").string()),
              std::string::npos)
        << e.what();
  }
}

TEST(Scene, DefaultSceneMatchesItsJsonFile) {
  const fs::path file = fs::path(VOXR_SOURCE_DIR) / "data" / "scenes" / "default.json";
  std::ifstream in(file);
  ASSERT_TRUE(in) << file;
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  EXPECT_EQ(nlohmann::json::parse(text, nullptr, true, true),
            nlohmann::json::parse(default_scene_json(), nullptr, true, true));

  const Scene built_in = default_scene(), loaded = load_scene(file);
  const TriangleSoup a = scene_triangles(built_in), b = scene_triangles(loaded);
  EXPECT_EQ(a.triangle_count(), b.triangle_count());
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(built_in.materials.size(), loaded.materials.size());
  EXPECT_EQ(built_in.camera.position, loaded.camera.position);
}

TEST(Scene, DefaultSceneHasWhatItPromises) {
  const Scene s = default_scene();
  bool kinds[3] = {false, false, false};
  for (const Material& m : s.materials) kinds[int(m.kind)] = true;
  EXPECT_TRUE(kinds[0] && kinds[1] && kinds[2]);
  ASSERT_EQ(s.meshes.size(), 5u);
  EXPECT_EQ(s.meshes[0].source, "generator:plane");
  EXPECT_EQ(s.meshes[1].source, "generator:torus");
  EXPECT_EQ(s.meshes[1].soup.triangle_count(), 800u);
  EXPECT_EQ(s.materials[s.meshes[1].material].kind, MaterialKind::kDielectric);
  EXPECT_EQ(s.meshes[2].source, "generator:vase");
  EXPECT_EQ(s.materials[s.meshes[2].material].kind, MaterialKind::kDielectric);
  EXPECT_EQ(s.meshes[4].source, "generator:tree");
  // The torus stands above the floor.
  Scene torus_only = s;
  torus_only.meshes = {s.meshes[1]};
  const Bounds torus = scene_bounds(torus_only);
  EXPECT_GT(torus.lo.y, 0.0f);
  EXPECT_GT(torus.size().y, 2.0f);  // upright: its 2.8-wide ring spans the height
  // Tree leaves are sheets, its trunk is not.
  const TriangleSoup world = scene_triangles(s);
  size_t sheets = 0;
  for (const glm::uvec4& t : world.triangles) sheets += s.materials[t.w].kind == MaterialKind::kSheet;
  EXPECT_EQ(sheets, 2u * 150u);
}

TEST(Scene, ExampleScenesLoad) {
  const fs::path dir = fs::path(VOXR_SOURCE_DIR) / "data" / "scenes";
  size_t loaded = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    try {
      const Scene s = load_scene(entry.path());
      EXPECT_GT(scene_triangles(s).triangle_count(), 0u);
      ++loaded;
    } catch (const Error& e) {
      // Scenes using fetched meshes need scripts/fetch-meshes.sh first.
      const std::string message = e.what();
      if (message.find("fetch-meshes") == std::string::npos) ADD_FAILURE() << message;
    }
  }
  EXPECT_GE(loaded, 2u);
}

}  // namespace
}  // namespace voxr
