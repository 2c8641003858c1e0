// voxr bench refraction end to end on a tiny case: the CSV's rows and finite errors, the Markdown, --help
// from voxr (forwarded to voxr-render), and one-line errors for an unknown method.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "cli_support.h"

namespace voxr {
namespace {

namespace fs = std::filesystem;
using test::read_csv;
using test::run_voxr;
using test::scratch;

const std::string kSphere = std::string(VOXR_SOURCE_DIR) + "/data/scenes/glass-sphere.json";

TEST(BenchRefractionCli, TinyRunWritesRowsWithFiniteErrors) {
  const fs::path prefix = scratch() / "r";
  const test::CliResult r =
      run_voxr("bench refraction --scenes " + kSphere +
               " --methods voxel-multi-dda-smooth,image-space,distance-maps --res 32 --size 64x48 "
               "--repeat 1 --warmup 0 --fresh 0 --out " +
               prefix.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const auto rows = read_csv(prefix.string() + ".csv");
  ASSERT_EQ(rows.size(), 4u);
  const std::vector<std::string> methods = {"reference-matched", "voxel-multi", "image-space",
                                            "distance-maps"};
  const std::vector<std::string> res = {"", "32", "", ""};
  for (size_t i = 0; i < rows.size(); ++i) {
    const auto& row = rows[i];
    EXPECT_EQ(row.at("scene"), "glass-sphere");
    EXPECT_EQ(row.at("method"), methods[i]);
    EXPECT_EQ(row.at("res"), res[i]) << methods[i];
    EXPECT_GT(std::stoull(row.at("triangles")), 0u);
    EXPECT_GT(std::stod(row.at("frame_ms")), 0.0) << methods[i];
    for (const char* column : {"rmse", "angle_mean_deg", "angle_p95_deg", "event_mismatch"}) {
      const double v = std::stod(row.at(column));
      EXPECT_TRUE(std::isfinite(v)) << methods[i] << " " << column << " " << row.at(column);
      EXPECT_GE(v, 0.0) << methods[i] << " " << column;
    }
    EXPECT_EQ(row.at("nonfinite"), "0") << methods[i];
  }
  EXPECT_EQ(rows[1].at("step"), "dda");
  EXPECT_EQ(rows[1].at("normals"), "smooth");
  EXPECT_GT(std::stoull(rows[1].at("grid_bytes")), 0u);
  EXPECT_GT(std::stod(rows[1].at("rmse")), 0.0);
  // Every method within image RMSE 0.1 of the matched reference on the sphere at 64 x 48 (the bound
  // RenderCli.EveryRefractionMethodRendersTheGlassSphere states: half what a flat image is off by).
  for (size_t i = 1; i < rows.size(); ++i) EXPECT_LE(std::stod(rows[i].at("rmse")), 0.1) << methods[i];
  EXPECT_GT(std::stod(rows[1].at("refraction_ms")), 0.0);
  EXPECT_EQ(rows[0].at("psnr"), "inf");
  // distance-maps' cost split: the layers and the tracing; the other methods render no layers.
  EXPECT_GT(std::stod(rows[3].at("dm_layers_ms")), 0.0);
  EXPECT_GT(std::stod(rows[3].at("refraction_ms")), 0.0);
  EXPECT_EQ(std::stod(rows[1].at("dm_layers_ms")), 0.0);
  const std::string md = test::slurp(prefix.string() + ".md");
  EXPECT_NE(md.find("## glass-sphere"), std::string::npos) << md;
  EXPECT_NE(md.find("Machine load"), std::string::npos) << md;
  EXPECT_NE(md.find("dm-layers ms"), std::string::npos) << md;
}

TEST(BenchRefractionCli, HelpIsForwardedFromVoxr) {
  const test::CliResult r = run_voxr("bench refraction --help");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("--methods"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--fresh"), std::string::npos) << r.out;
}

TEST(BenchRefractionCli, UnknownMethodIsAOneLineError) {
  for (const std::string method : {"voxel-three", "voxel-multi-dda", "voxel-multi-dda-flat"}) {
    const fs::path prefix = scratch() / "bad";
    const test::CliResult r = run_voxr("bench refraction --scenes " + kSphere + " --methods " + method +
                                       " --res 32 --size 64x48 --fresh 0 --out " + prefix.string());
    EXPECT_EQ(r.code, 1) << method;
    EXPECT_NE(r.err.find("unknown method '" + method + "'"), std::string::npos) << r.err;
    EXPECT_EQ(test::count_lines(r.err), 1) << r.err;
    EXPECT_FALSE(fs::exists(prefix.string() + ".csv"));
  }
}

}  // namespace
}  // namespace voxr
