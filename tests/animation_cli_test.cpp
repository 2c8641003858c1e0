// voxr render --frames N on deforming scenes: an output name with a frame field gets one image per frame,
// each posed at its own time (three different images), the report has one entry per frame, and a bad frame
// field is a one-line error; voxr bench animation (forwarded by voxr to voxr-render) writes its tables.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

#include "cli_support.h"
#include "io/image_file.h"

namespace voxr {
namespace {

namespace fs = std::filesystem;
using test::run_voxr;
using test::scratch;

const std::string kPassing = std::string(VOXR_SOURCE_DIR) + "/data/scenes/passing-objects.json";

TEST(AnimationCli, FramesAreWrittenToTheirNamesAndDiffer) {
  const fs::path dir = scratch() / "anim-frames";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path report = dir / "report.json";
  const test::CliResult r =
      run_voxr("render " + kPassing + " --size 64x48 --res 32 --shadow-res 32 --frames 3 -o " +
               (dir / "out_%04d.png").string() + " --report " + report.string());
  ASSERT_EQ(r.code, 0) << r.err;
  std::vector<ImageRgba> images;
  for (const char* name : {"out_0000.png", "out_0001.png", "out_0002.png"}) {
    ASSERT_TRUE(fs::exists(dir / name)) << name;
    images.push_back(read_image((dir / name).string()));
    EXPECT_EQ(images.back().width, 64u);
    EXPECT_EQ(images.back().height, 48u);
  }
  EXPECT_FALSE(fs::exists(dir / "out_0003.png"));
  EXPECT_NE(images[0].pixels, images[1].pixels);
  EXPECT_NE(images[1].pixels, images[2].pixels);
  EXPECT_NE(images[0].pixels, images[2].pixels);
  const nlohmann::json j = nlohmann::json::parse(test::slurp(report));
  EXPECT_TRUE(j["animated"].get<bool>());
  ASSERT_EQ(j["frames"].size(), 3u);
  for (size_t f = 0; f < 3; ++f) {
    const nlohmann::json& e = j["frames"][f];
    EXPECT_DOUBLE_EQ(e["time_s"].get<double>(), f / 24.0);
    EXPECT_GT(e["frame_ms"].get<double>(), 0.0);
    EXPECT_GT(e["pose_ms"].get<double>(), 0.0);
    EXPECT_TRUE(e["stages"].is_object());
    EXPECT_FALSE(e["stages"].empty());
  }
  EXPECT_NE(r.out.find("3 frames at 24 fps"), std::string::npos) << r.out;
}

TEST(AnimationCli, BadFramePatternsAreOneLineErrors) {
  const fs::path dir = scratch() / "anim-bad";
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const std::string name : {"out_%04d_%d.png", "out_%s.png", "out_%4d.png", "out_%%.png", "out_%0d.png",
                                 "out_%.png", "out_%0100d.png"}) {
    const test::CliResult r =
        run_voxr("render " + kPassing + " --size 16x12 --frames 2 -o " + (dir / name).string());
    EXPECT_NE(r.code, 0) << name;
    EXPECT_NE(r.err.find("a frame field is %d or %0Nd"), std::string::npos) << name << "\nstderr: " << r.err;
    EXPECT_EQ(test::count_lines(r.err), 1) << r.err;
  }
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(AnimationCli, BenchAnimationWritesOneRowPerSceneAndRefusesStaticScenes) {
  const fs::path out = scratch() / "bench-animation";
  const test::CliResult r = run_voxr("bench animation --scenes " + kPassing +
                                     " --frames 2 --size 32x24 --fresh 0 --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string csv = test::slurp(out.string() + ".csv");
  EXPECT_EQ(test::count_lines(csv), 2) << csv;  // header + passing-objects
  EXPECT_NE(csv.find("\npassing-objects,6274,voxel-multi,2,24,"), std::string::npos) << csv;
  const std::string md = test::slurp(out.string() + ".md");
  EXPECT_NE(md.find("| passing-objects | 6274 | voxel-multi |"), std::string::npos) << md;
  EXPECT_NE(md.find("Load average"), std::string::npos);

  const test::CliResult bad = run_voxr("bench animation --scenes " + std::string(VOXR_SOURCE_DIR) +
                                       "/data/scenes/gem.json --frames 1 --fresh 0 --out " + out.string());
  EXPECT_NE(bad.code, 0);
  EXPECT_NE(bad.err.find("gem.json: the scene is not animated"), std::string::npos) << bad.err;
  EXPECT_EQ(test::count_lines(bad.err), 1) << bad.err;
}

}  // namespace
}  // namespace voxr
