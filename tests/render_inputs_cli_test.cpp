// voxr render on the scene inputs of issue 20 (kinds 5, 7 and 8), end to end: a two-primitive glTF renders
// as its twin of generators, a scene 1e8 away as its twin at the origin, and the refusals name the place.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cl/device.h"
#include "cli_support.h"
#include "io/image_file.h"
#include "metrics/image_metrics.h"
#include "scene_inputs.h"

namespace voxr {
namespace {

namespace fs = std::filesystem;
using test::run_voxr;
using test::scratch;

// Renders `scene` to scratch()/NAME.exr with the flags every case here shares; expects exit 0 and nothing
// on stderr.
ImageRgba render(const fs::path& scene, const std::string& name) {
  const fs::path image = scratch() / (name + ".exr");
  const test::CliResult r =
      run_voxr("render " + scene.string() + " --size 80x60 --res 64 --shadow-res 64 -o " + image.string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "") << name;
  return read_image(image.string());
}

// Issue 20, kind 5 (../shared/cases/render/r05_gltf_materials.json): the box primitive of a glTF mesh takes
// the scene's second material (red), so the picture is that of the same scene built from generators. Before,
// every face took material 0 (a grey box: RMSE 0.072 here). Both pictures are the same triangles under the
// same light; they differ only in the floor's triangulation (bound: 0.005, measured 0.0).
TEST(RenderInputsCli, GltfPrimitiveMaterialsRenderAsTheirTwin) {
  const fs::path dir = scratch() / "r05";
  fs::create_directories(dir);
  test::write_floor_and_box_gltf(dir, "multi.gltf");
  const fs::path gltf_scene =
      test::write_scratch_file("r05/gltf.json", test::floor_and_box_scene("multi.gltf"));
  const fs::path twin_scene = test::write_scratch_file("r05/twin.json", test::floor_and_box_scene(""));
  const ImageRgba a = render(gltf_scene, "r05-gltf"), b = render(twin_scene, "r05-twin");
  EXPECT_LE(rmse(a, b), 0.005);
}

// Issue 20, kind 8 (r08_far_scene.json): the scene translated by 1e8 along x, with no camera, gets the
// default camera of its twin at the origin and renders its picture (before: RMSE 0.23, a camera framed from
// float bounds). The soups' float positions are the same bit for bit (1e8 is a multiple of the power of two
// above the scene's size); bound 0.005 (measured 0.0).
TEST(RenderInputsCli, FarSceneRendersAsItsNearTwin) {
  const fs::path near =
      test::write_scratch_file("r08-near.json", test::far_scene_json(glm::dvec3(0.0), true));
  const fs::path far =
      test::write_scratch_file("r08-far.json", test::far_scene_json(glm::dvec3(1e8, 0.0, 0.0), true));
  EXPECT_LE(rmse(render(far, "r08-far"), render(near, "r08-near")), 0.005);
}

// Exit 1 for a refused input, 2 for a flag CLI11 refuses.
void expect_one_line_error(const test::CliResult& r, const std::vector<std::string>& needles, int code = 1) {
  EXPECT_EQ(r.code, code) << r.err;
  for (const std::string& n : needles)
    EXPECT_NE(r.err.find(n), std::string::npos) << n << "\nstderr: " << r.err;
  EXPECT_EQ(test::count_lines(r.err), 1) << r.err;
}

// Issue 20, kind 7: each refusal names the file, the place and the value as the user wrote them.
TEST(RenderInputsCli, RefusalsNameThePlace) {
  const fs::path out = scratch() / "place.png";
  // r07_huge_number.json: a number beyond double range (before: nlohmann's raw message).
  const fs::path huge = test::write_scratch_file(
      "r07-huge.json", R"({"meshes":[{"generator":"box","transform":{"scale":1e400}}]})");
  expect_one_line_error(run_voxr("render " + huge.string() + " -o " + out.string()),
                        {huge.string() + ": 'meshes[0].transform.scale' holds the number '1e400'"});
  // r07_point_light_on_floor.json: the light as written, (1, 0, 1), not anchor-relative (9, 0, 9).
  const fs::path light = test::write_scratch_file("r07-light.json", R"({
    "materials": [{"name": "floor", "kind": "opaque"}, {"name": "red", "kind": "opaque"}],
    "meshes": [{"generator": "plane", "params": {"size": [6, 6]}, "material": "floor"},
               {"generator": "sphere", "params": {"radius": 0.5}, "material": "red",
                "transform": {"translate": [0, 0.6, 0]}}],
    "light": {"type": "point", "position": [1, 0, 1], "intensity": [5, 5, 5]},
    "camera": {"position": [0, 2, 4], "look_at": [0, 0.4, 0], "width": 40, "height": 30}})");
  expect_one_line_error(run_voxr("render " + light.string() + " --shadow-res 64 -o " + out.string()),
                        {light.string() + ": 'light.position' (1, 0, 1) is beside or among the receivers"});
  // --size: the whole text quoted, and the form expected.
  for (const std::string size : {"160x", "160x120x3", "x120"})
    expect_one_line_error(run_voxr("render --size " + size + " -o " + out.string()),
                          {"--size: '" + size + "': expected WIDTHxHEIGHT"}, 2);
  EXPECT_FALSE(fs::exists(out));
}

// Issue 20, kind 7: an image beyond the device's largest buffer names --size as what to reduce (before: it
// advised --res). Skipped on a device whose largest buffer holds 16384 x 16384 surface samples (16 GiB).
TEST(RenderInputsCli, ImageBeyondTheLargestBufferNamesSize) {
  const uint64_t bytes = 16384ull * 16384ull * 64ull;
  const DeviceInfo device = select_device("");
  if (device.max_allocation >= bytes) GTEST_SKIP() << device.label() << " holds a 16384x16384 image";
  const fs::path out = scratch() / "huge.png";
  expect_one_line_error(run_voxr("render --size 16384x16384 -o " + out.string()),
                        {"a 16384x16384 image needs 16384.0 MiB", "use a smaller --size"});
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace voxr
