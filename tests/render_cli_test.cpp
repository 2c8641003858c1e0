// voxr render end to end: the image and the report with every shadow method, the comparison with the
// reference, and one-line errors for bad flags and outputs.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

#include "cli_support.h"
#include "core/default_scene.h"
#include "io/image_file.h"
#include "metrics/image_metrics.h"

namespace voxr {
namespace {

namespace fs = std::filesystem;
using test::run_voxr;
using test::scratch;

TEST(RenderCli, EveryMethodWritesAnImageAndAReport) {
  for (const std::string method :
       {"voxel", "uniform", "filter", "opaque", "voxel-exact", "reference", "none"}) {
    const fs::path image = scratch() / ("render-" + method + ".png");
    const fs::path report = scratch() / ("render-" + method + ".json");
    const test::CliResult r = run_voxr("render --size 64x48 --shadow-res 64 --shadows " + method + " -o " +
                                       image.string() + " --report " + report.string());
    ASSERT_EQ(r.code, 0) << method << ": " << r.err;
    const ImageRgba img = read_image(image.string());
    EXPECT_EQ(img.width, 64u);
    EXPECT_EQ(img.height, 48u);
    const nlohmann::json j = nlohmann::json::parse(test::slurp(report));
    EXPECT_EQ(j["shadows"], method);
    EXPECT_GT(j["ms"]["frame"].get<double>(), 0.0);
    if (method == "voxel-exact") {
      EXPECT_EQ(j["triangle_grid"]["dims"][0], 64)
          << "the triangle grid: --shadow-res along the longest side";
    } else if (method != "reference" && method != "none") {
      EXPECT_TRUE(j.contains("light_grid")) << method;
    }
  }
}

TEST(RenderCli, CompareReferenceReportsErrorsAndWritesTheErrorImage) {
  const fs::path image = scratch() / "compare.png";
  const fs::path report = scratch() / "compare.json";
  const test::CliResult r = run_voxr("render --size 80x60 --shadow-res 128 --compare-reference -o " +
                                     image.string() + " --report " + report.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(test::slurp(report));
  // The built-in scene has glass: the refraction is measured against the matched reference, the shadows at
  // the receivers the paths end on.
  const auto& c = j["compare_reference"]["shadows"];
  EXPECT_GT(c["receivers"].get<uint64_t>(), 1000u);
  EXPECT_GE(c["transmittance_rmse"].get<double>(), 0.0);
  EXPECT_LT(c["transmittance_rmse"].get<double>(), 0.1);
  EXPECT_TRUE(fs::exists(scratch() / "compare.shadow-error.png"));
  EXPECT_NE(r.out.find("vs exact"), std::string::npos) << r.out;
  const auto& f = j["compare_reference"]["refraction"];
  EXPECT_GT(f["refracted_pixels"].get<uint64_t>(), 100u);
  EXPECT_EQ(f["nonfinite_pixels"].get<uint64_t>(), 0u);
  EXPECT_GT(f["psnr"].get<double>(), 15.0);
  EXPECT_TRUE(fs::exists(scratch() / "compare.error.png"));
  EXPECT_NE(r.out.find("vs matched"), std::string::npos) << r.out;
}

// The README's first command renders the built-in scene with the default methods; that picture must be free
// of speckle (issue 19): whole-image PSNR >= 35 dB against the exact reference (`--refraction reference`,
// exact shadows), both at the scene's own camera and size, as the README renders it.
TEST(RenderCli, BuiltInSceneWithTheDefaultMethodsMatchesTheReference) {
  const fs::path defaults = scratch() / "builtin-defaults.exr";
  const fs::path reference = scratch() / "builtin-reference.exr";
  const test::CliResult d = run_voxr("render -o " + defaults.string());
  ASSERT_EQ(d.code, 0) << d.err;
  const test::CliResult r = run_voxr("render --refraction reference -o " + reference.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const ImageRgba a = read_image(defaults), b = read_image(reference);
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  const Scene builtin = default_scene();
  EXPECT_EQ(a.width, builtin.camera.width) << "the README's picture, at the scene camera's size";
  EXPECT_EQ(a.height, builtin.camera.height);
  EXPECT_GE(psnr(a, b), 35.0) << "RMSE " << rmse(a, b);
}

// Issue 20, kind 2 (../shared/cases/render/r02_ior1_sphere.json): a clear sphere of IOR 1 and no absorption
// is invisible: the picture of the same scene without it, in the exact methods and both references
// (Schlick's formula drew a ring at its silhouette: F must be 0 where the indices match).
TEST(RenderCli, IndexMatchedSphereIsInvisible) {
  const std::string floor_and_camera =
      R"("light": {"type": "directional", "direction": [-0.4, -1, -0.5], "intensity": [0.9, 0.9, 0.9]},
         "camera": {"position": [0, 1.6, 3.2], "look_at": [0, 0.5, 0], "fov_deg": 45, "width": 160,
                    "height": 120},
         "environment": {"procedural": "checker"})";
  const fs::path with = test::write_scratch_file(
      "ior1-sphere.json",
      R"({"materials": [{"name": "floor", "kind": "opaque", "color": [0.7, 0.7, 0.65]},
                        {"name": "clear", "kind": "dielectric", "ior": 1.0, "absorption": [0, 0, 0]}],
          "meshes": [{"generator": "plane", "params": {"size": [6, 6]}, "material": "floor"},
                     {"generator": "sphere", "params": {"radius": 0.5, "stacks": 24, "slices": 48},
                      "material": "clear", "transform": {"translate": [0, 0.6, 0]}}], )" +
          floor_and_camera + "}");
  const fs::path without = test::write_scratch_file(
      "no-sphere.json", R"({"materials": [{"name": "floor", "kind": "opaque", "color": [0.7, 0.7, 0.65]}],
          "meshes": [{"generator": "plane", "params": {"size": [6, 6]}, "material": "floor"}], )" +
                            floor_and_camera + "}");
  for (const std::string methods : {"--refraction reference", "--refraction reference-full",
                                    "--refraction voxel-exact --shadows voxel-exact"}) {
    const fs::path a = scratch() / "ior1-with.exr", b = scratch() / "ior1-without.exr";
    const test::CliResult r1 = run_voxr("render " + with.string() + " " + methods + " -o " + a.string());
    ASSERT_EQ(r1.code, 0) << methods << ": " << r1.err;
    const test::CliResult r2 = run_voxr("render " + without.string() + " " + methods + " -o " + b.string());
    ASSERT_EQ(r2.code, 0) << methods << ": " << r2.err;
    EXPECT_LE(rmse(read_image(a), read_image(b)), 1e-3) << methods;
  }
}

TEST(RenderCli, DistanceMapOptionsAreCheckedAndReported) {
  const std::string scene = std::string(VOXR_SOURCE_DIR) + "/data/scenes/glass-sphere.json";
  const fs::path image = scratch() / "dm.png";
  for (const char* bad :
       {"--layers 0", "--layers 17", "--layer-res 4", "--layer-res 4096", "--dm-depth 0", "--dm-depth 33"}) {
    const test::CliResult r =
        run_voxr("render " + scene + " --refraction distance-maps " + bad + " -o " + image.string());
    EXPECT_NE(r.code, 0) << bad;
  }
  const fs::path report = scratch() / "dm.json";
  const test::CliResult r = run_voxr("render " + scene +
                                     " --size 64x48 --shadow-res 64 --refraction distance-maps --layers 2 "
                                     "--layer-res 32 --dm-depth 8 -o " +
                                     image.string() + " --report " + report.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(test::slurp(report));
  EXPECT_EQ(j["refraction_options"]["layers"], 2);
  EXPECT_EQ(j["refraction_options"]["layer_res"], 32);
  EXPECT_EQ(j["refraction_options"]["max_events"], 8);
  EXPECT_TRUE(j["ms"]["stages"].contains("dm-layers")) << j["ms"].dump();
}

TEST(RenderCli, EveryRefractionMethodRendersTheGlassSphere) {
  const std::string scene = std::string(VOXR_SOURCE_DIR) + "/data/scenes/glass-sphere.json";
  for (const std::string method : {"voxel-multi", "voxel-two", "voxel-exact", "image-space", "distance-maps",
                                   "reference", "reference-full", "none"}) {
    const fs::path image = scratch() / ("refract-" + method + ".exr");
    const fs::path report = scratch() / ("refract-" + method + ".json");
    const test::CliResult r = run_voxr("render " + scene +
                                       " --size 64x48 --shadow-res 64 --res 64 --step papers "
                                       "--normals voxel --refraction " +
                                       method + " -o " + image.string() + " --report " + report.string());
    ASSERT_EQ(r.code, 0) << method << ": " << r.err;
    const nlohmann::json j = nlohmann::json::parse(test::slurp(report));
    EXPECT_EQ(j["refraction"], method);
    EXPECT_EQ(j["environment"], "checker");
    EXPECT_EQ(j.contains("refraction_grid"),
              method == "voxel-multi" || method == "voxel-two" || method == "voxel-exact")
        << method;
    const ImageRgba img = read_image(image.string());
    for (const glm::vec4& p : img.pixels)
      ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
  }
}

TEST(RenderCli, BadFlagsAndOutputsAreOneLineErrors) {
  struct Case {
    std::string args, needle;
  };
  const fs::path out = scratch() / "bad.png";
  for (const Case& c : std::vector<Case>{
           {"render -o " + (scratch() / "x.bmp").string(), "x.bmp: the image format is chosen by extension"},
           {"render --shadows soft -o " + out.string(), "unknown shadow method 'soft'"},
           {"render --shadows uniform --mode conservative -o " + out.string(),
            "--mode applies to --shadows voxel"},
           {"render --size 64 -o " + out.string(), "--size: '64': expected WIDTHxHEIGHT"},
           {"render --shadows reference --refraction none --compare-reference -o " + out.string(),
            "there is nothing to measure"},
           {"render --refraction reference --compare-reference -o " + out.string(),
            "there is nothing to measure"},
           {"render --refraction bent -o " + out.string(), "unknown refraction method 'bent'"},
           {"render --refraction reference --shadows voxel -o " + out.string(), "does not apply"},
           {"render " + std::string(VOXR_SOURCE_DIR) +
                "/data/scenes/foliage.json --shadows none --compare-reference -o " + out.string(),
            "foliage.json: --compare-reference has nothing to measure"},
           {"render --layers 2 -o " + out.string(),
            "--layers applies to --refraction distance-maps only, not --refraction voxel-exact"},
           {"render --refraction image-space --dm-depth 4 -o " + out.string(),
            "--dm-depth applies to --refraction distance-maps only, not --refraction image-space"},
           {"render --step big -o " + out.string(), "unknown step rule 'big'"},
           {"render --normals wavy -o " + out.string(), "unknown normal kind 'wavy'"},
           {"render --res 1 -o " + out.string(), "--res"},
           {"render --shadow-res 2 -o " + out.string(), "--shadow-res"},
           {"render " + (scratch() / "missing.json").string() + " -o " + out.string(),
            "missing.json: no such file"},
       }) {
    const test::CliResult r = run_voxr(c.args);
    EXPECT_NE(r.code, 0) << c.args;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << c.args << "\nstderr: " << r.err;
    EXPECT_EQ(test::count_lines(r.err), 1) << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
}

}  // namespace
}  // namespace voxr
