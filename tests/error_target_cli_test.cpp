// --error-target end to end: voxr voxelize and voxr render choose the smallest grid measured to meet the
// target, report the search and the saving against 512, and refuse what they cannot choose.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

#include "cli_support.h"

namespace voxr {
namespace {

namespace fs = std::filesystem;
using test::run_voxr;
using test::scratch;

// The choice is the smallest measured to meet the target: the lowest resolution, or one within the search's
// 5 % (2 voxels) above a measured miss.
void expect_smallest(const nlohmann::json& search, double target, uint32_t lowest) {
  const uint32_t chosen = search["res"].get<uint32_t>();
  if (chosen == lowest) return;
  bool miss_below = false;
  for (const auto& t : search["trials"]) {
    const uint32_t r = t["res"].get<uint32_t>();
    const double e = t.contains("error") ? t["error"].get<double>() : t["rmse"].get<double>();
    if (r < chosen && r + std::max(2u, chosen / 20) >= chosen && e > target) miss_below = true;
  }
  EXPECT_TRUE(miss_below) << search.dump();
}

TEST(ErrorTargetCli, VoxelizeChoosesTheSmallestGridThatMeetsTheSurfaceError) {
  const fs::path report = scratch() / "target-voxelize.json";
  const test::CliResult r = run_voxr("voxelize --error-target 0.004 --report " + report.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json t = nlohmann::json::parse(test::slurp(report))["error_target"];
  EXPECT_TRUE(t["met"].get<bool>()) << t.dump();
  EXPECT_LE(t["error"].get<double>(), 0.004);
  expect_smallest(t, 0.004, 16);
  // The job ran on the chosen grid, and the fixed 512 grid it replaces holds more.
  const nlohmann::json j = nlohmann::json::parse(test::slurp(report));
  EXPECT_EQ(*std::max_element(j["dims"].begin(), j["dims"].end()), t["res"]);
  EXPECT_GT(t["fixed"]["device_bytes"].get<uint64_t>(), j["device_bytes"].get<uint64_t>());
  EXPECT_NE(r.out.find("vs res 512"), std::string::npos) << r.out;
}

TEST(ErrorTargetCli, RenderChoosesTheRefractionAndShadowGrids) {
  const std::string scene = std::string(VOXR_SOURCE_DIR) + "/data/scenes/glass-sphere.json";
  const fs::path report = scratch() / "target-render.json";
  // The papers' methods: the exact defaults have no grid to choose (their error is 0 at any grid).
  const test::CliResult r = run_voxr(
      "render " + scene + " --refraction voxel-multi --shadows voxel --size 96x72 --error-target 0.1 -o " +
      (scratch() / "target.png").string() + " --report " + report.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(test::slurp(report));
  const nlohmann::json& t = j["error_target"];
  EXPECT_EQ(t["sample"][0], 48);
  EXPECT_EQ(t["sample"][1], 36);
  // The glass sphere's refraction and shadows each reach their share of 0.1 well inside the search's range
  // (voxel-multi and voxel shadows fall as 1 / resolution): the search must meet both, on the smallest grid.
  for (const char* part : {"refraction", "shadows"}) {
    ASSERT_TRUE(t.contains(part)) << t.dump();
    const nlohmann::json& s = t[part];
    ASSERT_TRUE(s["met"].get<bool>()) << part << ": " << s.dump();
    EXPECT_LE(s["rmse"].get<double>(), s["budget"].get<double>()) << part;
    EXPECT_GT(s["budget"].get<double>(), 0.0) << part;
    expect_smallest(s, s["budget"].get<double>(), 16);
  }
  // The frame ran on the chosen grids.
  EXPECT_EQ(*std::max_element(j["refraction_grid"]["dims"].begin(), j["refraction_grid"]["dims"].end()),
            t["refraction"]["res"]);
  EXPECT_GT(t["fixed"]["device_bytes"].get<uint64_t>(), t["device_bytes"].get<uint64_t>());
}

TEST(ErrorTargetCli, WhatCannotBeChosenIsAOneLineError) {
  const std::string out = (scratch() / "target-bad.png").string();
  struct Case {
    std::string args, needle;
  };
  for (const Case& c : std::vector<Case>{
           {"voxelize --error-target 0.01 --res 64", "--error-target chooses the resolution"},
           {"render --error-target 0.01 --res 64 -o " + out, "leave them out"},
           {"render --error-target 0.01 --refraction reference -o " + out, "has none"},
           {"render --error-target 0.01 --refraction none --shadows reference -o " + out, "there is none"},
           {"render --error-target 0.01 --refraction none --shadows voxel-exact -o " + out, "there is none"},
           {"voxelize --error-target -1", "--error-target"}}) {
    const test::CliResult r = run_voxr(c.args);
    EXPECT_NE(r.code, 0) << c.args;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << c.args << ": " << r.err;
    EXPECT_EQ(test::count_lines(r.err), 1) << c.args << ": " << r.err;
  }
}

}  // namespace
}  // namespace voxr
