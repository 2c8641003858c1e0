// Scene inputs read right or refused naming the place (issue 20, kinds 5, 7 and 8): a mesh file's material
// ids mapped by the scene's list (glTF primitives, OBJ usemtl groups) with a warning when they disagree,
// numbers beyond double or float range named by key path, positions kept in double, and the default camera
// and light of a far-away scene fitted in double (the same as at the origin) with a warning when the scene is
// too small for the precision of its coordinates.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "core/scene.h"
#include "scene_inputs.h"
#include "test_support.h"
#include "util/error.h"

namespace voxr {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

std::string scene_error(const std::string& text, const fs::path& base = ".") {
  try {
    parse_scene(text, "s.json", base);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

const char* kMaterials = R"("materials": [{"name": "a", "kind": "opaque"}, {"name": "b", "kind": "opaque"},
                                          {"name": "c", "kind": "opaque"}])";

// The scene material of each world triangle of the floor and of the box.
struct FloorAndBox {
  std::vector<uint32_t> floor, box;
};
FloorAndBox materials_by_place(const Scene& scene) {
  const TriangleSoup soup = scene_triangles(scene);
  FloorAndBox out;
  for (const glm::uvec4& t : soup.triangles)  // the floor reaches x = +-3, the box +-0.5
    (std::abs(soup.anchor.x + soup.positions[t.x].x) > 1.0 ? out.floor : out.box).push_back(t.w);
  return out;
}

void expect_all(const std::vector<uint32_t>& ids, uint32_t want, size_t count, const char* what) {
  EXPECT_EQ(ids.size(), count) << what;
  for (uint32_t id : ids) EXPECT_EQ(id, want) << what;
}

// Kind 5: the floor primitive (material 0) and the box primitive (material 1) of one glTF mesh take the
// scene materials the list names for ids 0 and 1, in any order; the same for an OBJ's usemtl groups.
TEST(SceneInputs, FileMaterialIdsMapByTheScenesList) {
  TempDir dir;
  test::write_floor_and_box_gltf(dir.path(), "multi.gltf");
  dir.write("multi.obj", test::floor_and_box_obj());
  for (const char* file : {"multi.gltf", "multi.obj"}) {
    SCOPED_TRACE(file);
    const Scene s = parse_scene(
        fmt::format(R"({{{}, "meshes": [{{"file": "{}", "material": ["c", "a"]}}]}})", kMaterials, file),
        "s.json", dir.path());
    const FloorAndBox ids = materials_by_place(s);
    expect_all(ids.floor, 2, 2, "floor: file id 0 -> 'c'");
    expect_all(ids.box, 0, 12, "box: file id 1 -> 'a'");
    EXPECT_TRUE(s.meshes[0].warnings.empty());
    // One name gives every face that material.
    const FloorAndBox one = materials_by_place(
        parse_scene(fmt::format(R"({{{}, "meshes": [{{"file": "{}", "material": "b"}}]}})", kMaterials, file),
                    "s.json", dir.path()));
    expect_all(one.floor, 1, 2, "floor");
    expect_all(one.box, 1, 12, "box");
  }
}

// Kind 5: a list longer than the ids the file carries is read with one warning naming the file and the
// counts; a shorter one is an error naming the file.
TEST(SceneInputs, MaterialListAndFileDisagree) {
  TempDir dir;
  const fs::path gltf = test::write_floor_and_box_gltf(dir.path(), "multi.gltf");
  const Scene s = parse_scene(
      fmt::format(R"({{{}, "meshes": [{{"file": "multi.gltf", "material": ["a", "b", "c"]}}]}})", kMaterials),
      "s.json", dir.path());
  ASSERT_EQ(s.meshes[0].warnings.size(), 1u);
  EXPECT_EQ(s.meshes[0].warnings[0],
            gltf.string() +
                ": carries 2 material ids (0..1) but 'meshes[0].material' in s.json lists 3 "
                "materials; the last 1 is unused");
  EXPECT_EQ(scene_error(
                fmt::format(R"({{{}, "meshes": [{{"file": "multi.gltf", "material": ["a"]}}]}})", kMaterials),
                dir.path()),
            "s.json: 'meshes[0].material' must list a material for each of the material ids 0..1 that " +
                gltf.string() + " carries (got [\"a\"])");
  // A file without ids (one material) and a list of two: the second is unused.
  dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const Scene t = parse_scene(
      fmt::format(R"({{{}, "meshes": [{{"file": "tri.obj", "material": ["a", "b"]}}]}})", kMaterials),
      "s.json", dir.path());
  ASSERT_EQ(t.meshes[0].warnings.size(), 1u);
  EXPECT_EQ(t.meshes[0].warnings[0], (dir.path() / "tri.obj").string() +
                                         ": carries 1 material id (0..0) but 'meshes[0].material' in s.json "
                                         "lists 2 materials; the last 1 is unused");
}

// Kind 7: a number beyond a double's range is named by its key path (nlohmann's parser refuses it while
// parsing, with no line or column).
TEST(SceneInputs, NumberBeyondDoubleRangeNamesTheKeyPath) {
  EXPECT_EQ(scene_error(R"({"meshes":[{"generator":"box","transform":{"scale":1e400}}]})"),
            "s.json: 'meshes[0].transform.scale' holds the number '1e400', which is out of range (beyond "
            "1.8e308)");
  EXPECT_EQ(scene_error(R"({"meshes":[{"generator":"box"}], "camera": {"position": [0, -1e999, 5]}})"),
            "s.json: 'camera.position[1]' holds the number '-1e999', which is out of range (beyond 1.8e308)");
  EXPECT_EQ(scene_error("1e400"),
            "s.json: the top-level value holds the number '1e400', which is out of range (beyond 1.8e308)");
  // A long number is quoted cut.
  const std::string what = scene_error(R"({"meshes": )" + std::string(200, '9') + "e999}");
  EXPECT_EQ(what, "s.json: 'meshes' holds the number '" + std::string(37, '9') +
                      "...', which is out of range (beyond 1.8e308)");
}

// Kind 7: a finite double beyond float range is said to be out of float range, not "not finite".
TEST(SceneInputs, FiniteNumberBeyondFloatRangeIsOutOfFloatRange) {
  const std::string box = R"("meshes": [{"generator": "box")";
  EXPECT_EQ(
      scene_error("{" + box + R"(, "transform": {"scale": 1e+300}}]})"),
      "s.json: 'meshes[0].transform.scale' is out of float range (the magnitude must be at most 3.4e38) "
      "(got 1e+300)");
  EXPECT_EQ(scene_error("{" + box + R"(, "transform": {"translate": [0, 1e300, 0]}}]})"),
            "s.json: 'meshes[0].transform.translate' is out of float range (the magnitude must be at most "
            "3.4e38) (got [0,1e+300,0])");
  EXPECT_EQ(scene_error("{" + box + R"(}], "grid": {"bounds": [0, 0, 0, 1, 1, -1e300]}})"),
            "s.json: 'grid.bounds' is out of float range (the magnitude must be at most 3.4e38) (got "
            "[0,0,0,1,1,-1e+300])");
  EXPECT_EQ(scene_error("{" + box + R"(}], "light": {"type": "point", "position": [3e38, 0, 4e38]}})"),
            "s.json: 'light.position' is out of float range (the magnitude must be at most 3.4e38) (got "
            "[3e+38,0,4e+38])");
}

// Kind 8: camera and light positions keep the digits the file gives (a float would round 1e8 + 0.25 to 1e8).
TEST(SceneInputs, PositionsKeepDoublePrecision) {
  const Scene s = parse_scene(R"({"meshes": [{"generator": "box"}],
      "light": {"type": "point", "position": [100000000.25, 1, 2]},
      "camera": {"position": [100000000.5, 0, 5], "look_at": [100000000.25, 0, 0]}})",
                              "s.json", ".");
  EXPECT_EQ(s.light.position, glm::dvec3(100000000.25, 1, 2));
  EXPECT_EQ(s.camera.position, glm::dvec3(100000000.5, 0, 5));
  EXPECT_EQ(s.camera.look_at, glm::dvec3(100000000.25, 0, 0));
}

// Kind 8: a scene translated by 1e8 (a multiple of the power of two above its size, so its float positions
// are the same) gets the default camera and light of the scene at the origin, translated.
TEST(SceneInputs, FarSceneGetsTheDefaultsOfItsNearTwin) {
  const glm::dvec3 shift(1e8, 0.0, -2e8);
  const Scene near = parse_scene(test::far_scene_json(glm::dvec3(0.0), false), "near.json", ".");
  const Scene far = parse_scene(test::far_scene_json(shift, false), "far.json", ".");
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(far.camera.position[c] - shift[c], near.camera.position[c], 1e-6) << c;
    EXPECT_NEAR(far.camera.look_at[c] - shift[c], near.camera.look_at[c], 1e-6) << c;
    EXPECT_NEAR(far.light.position[c] - shift[c], near.light.position[c], 1e-6) << c;
  }
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(far.light.intensity[c] / near.light.intensity[c], 1.0, 1e-6) << c;
  EXPECT_TRUE(near.warnings.empty());
  EXPECT_TRUE(far.warnings.empty()) << far.warnings[0];
  // A mesh file whose coordinates a float cannot hold (123456789.37: floats are 8 apart there) is framed in
  // double as well.
  TempDir dir;
  const glm::dvec3 odd(123456789.37, -0.25, 98765432.1);
  dir.write("near.obj", test::floor_and_box_obj());
  dir.write("far.obj", test::floor_and_box_obj(odd));
  const Scene near_mesh = load_input(dir.path() / "near.obj"), far_mesh = load_input(dir.path() / "far.obj");
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(far_mesh.camera.position[c] - odd[c], near_mesh.camera.position[c], 1e-6) << c;
    EXPECT_NEAR(far_mesh.camera.look_at[c] - odd[c], near_mesh.camera.look_at[c], 1e-6) << c;
    EXPECT_NEAR(far_mesh.light.position[c] - odd[c], near_mesh.light.position[c], 1e-6) << c;
  }
}

// Kind 8: a scene smaller than 65 536 steps of its coordinates is read with one warning; at 1e20 (its x
// collapsed) less than one step.
TEST(SceneInputs, SceneBelowThePrecisionOfItsCoordinatesWarns) {
  const Scene quantised = parse_scene(test::far_scene_json(glm::dvec3(1e13, 0, 0), false), "q.json", ".");
  ASSERT_EQ(quantised.warnings.size(), 1u);
  EXPECT_EQ(
      quantised.warnings[0],
      "q.json: the scene spans 6 units at 1e+13 from the origin, where coordinates are 0.00195 apart: "
      "fewer than 65536 steps across it, so its positions are quantised; translate it nearer the origin");
  const Scene collapsed = parse_scene(test::far_scene_json(glm::dvec3(1e20, 0, 0), false), "c.json", ".");
  ASSERT_EQ(collapsed.warnings.size(), 1u);
  EXPECT_EQ(collapsed.warnings[0],
            "c.json: the scene spans 6 units at 1e+20 from the origin, where coordinates are 1.64e+04 apart: "
            "less than one step across it, so its positions are quantised; translate it nearer the origin");
  // 1e8 is fine (the far scene of issue 20), whether or not the scene gives its camera and light.
  EXPECT_TRUE(parse_scene(test::far_scene_json(glm::dvec3(1e8, 0, 0), true), "f.json", ".").warnings.empty());
}

// Found by fuzz_scene (a key written "\\\\...\nname" in a material): a key, name or path holding a control
// character was printed raw and split the message over lines. Every message quoting them stays one line
// and bounded.
TEST(SceneInputs, KeysNamesAndPathsWithControlCharactersAreQuotedOnOneLine) {
  const std::string box = R"("meshes": [{"generator": "box"}])";
  const std::string m = R"({"name": "a", "kind": "opaque"})";
  const std::string long_key(300, 'k');
  struct Case {
    std::string text, expected;
  };
  const Case cases[] = {
      {"{" + box + R"(, "materials": [)" + m + R"(, {"\\\nname": "b", "kind": "opaque"}]})",
       R"(s.json: unknown key 'materials[1]."\\\nname"' (did you mean 'materials[1].name'?))"},
      {"{" + box + R"(, "camera": {"pos\u0001": 1}})",
       R"(s.json: unknown key 'camera."pos\u0001"' (allowed here: position, look_at, up, fov_deg, width, height))"},
      {"{" + box + ", \"" + long_key + "\": 1}",
       "s.json: unknown key '\"" + std::string(36, 'k') +
           "...' (allowed here: materials, meshes, light, camera, environment, grid, animation)"},
      {R"({"meshes": [{"generator": "box"}], "a\nb": 1, "a\nb": 2})", R"(s.json: duplicate key '"a\nb"')"},
      {R"({"materials": [{"name": "x\ny", "kind": "opaque"}], "meshes": [{"generator": "box", "material": "z\tw"}]})",
       R"(s.json: 'meshes[0].material' names no material: "z\tw" (materials: "x\ny"))"},
      {R"({"materials": [{"name": "x\ny", "kind": "opaque"}, {"name": "x\ny", "kind": "opaque"}], )" + box +
           "}",
       R"(s.json: 'materials[1].name' repeats the material name "x\ny")"},
      {R"({"materials": [{"name": "a", "kind": "op\naque"}], )" + box + "}",
       R"(s.json: 'materials[0].kind' must be opaque, dielectric or sheet (got "op\naque"))"},
      {R"({"meshes": [{"generator": "bo\rx"}]})",
       R"(s.json: 'meshes[0].generator' must be one of torus, sphere, box, vase, tree, plane, foliage (got "bo\rx"))"},
      {R"({"meshes": [{"file": "a\nb.obj"}]})",
       R"(s.json: 'meshes[0].file' must be a path without control characters (got "a\nb.obj"))"},
      {"{" + box + R"(, "environment": {"image": "sky\n.exr"}})",
       R"(s.json: 'environment.image' must be a path without control characters (got "sky\n.exr"))"},
  };
  for (const Case& c : cases) {
    const std::string what = scene_error(c.text);
    EXPECT_EQ(what, c.expected) << c.text;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

// The scene fuzzer's seeds (fuzz/corpus/scene) are scenes: each loads.
TEST(SceneInputs, FuzzSeedsAreScenes) {
  size_t files = 0;
  for (const fs::directory_entry& e :
       fs::directory_iterator(fs::path(VOXR_SOURCE_DIR) / "fuzz/corpus/scene")) {
    SCOPED_TRACE(e.path().string());
    EXPECT_FALSE(load_scene(e.path()).meshes.empty());
    ++files;
  }
  EXPECT_EQ(files, 23u);
}

}  // namespace
}  // namespace voxr
