// voxr bench pareto end to end on the smallest case: the CSV's columns, every effect, finite errors, the
// front's membership in each (effect, scene), the page and its pictures; one-line errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>

#include "cli_support.h"

namespace voxr {
namespace {

namespace fs = std::filesystem;
using test::read_csv;
using test::run_voxr;
using test::scratch;

const std::string kSphere = std::string(VOXR_SOURCE_DIR) + "/data/scenes/glass-sphere.json";

TEST(BenchParetoCli, TinyRunWritesEveryEffectWithItsFront) {
  const fs::path dir = scratch() / "pareto";
  const fs::path page = dir / "docs" / "pareto.md";
  fs::create_directories(dir);
  const test::CliResult r =
      run_voxr("bench pareto --out " + (dir / "p").string() + " --doc " + page.string() +
               " --vox-meshes torus --vox-res 16 --vox-methods grid,slice-center --vox-samples 2000"
               " --shadow-scenes default --shadow-res 16 --shadow-methods voxel-center,opaque"
               " --refraction-scenes " +
               kSphere +
               " --refraction-res 16 --refraction-methods voxel-two,voxel-exact,image-space --size 48x32 "
               "--repeat 1 --warmup 0");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string header = test::slurp(dir / "p.csv").substr(0, test::slurp(dir / "p.csv").find('\n'));
  EXPECT_EQ(
      header,
      "effect,scene,method,resolution,time_ms,time_ms_min,time_ms_max,time_measure,error,error_measure,bytes,"
      "load_1min,reference,front");
  const auto rows = read_csv(dir / "p.csv");
  ASSERT_EQ(rows.size(), 9u);
  // Each rendering effect's exact reference is a run of its own (error 0), before the methods.
  // The papers' voxel methods are named with their step rule and normals, voxel-exact has none.
  const std::vector<std::string> effects = {"voxelization", "voxelization", "shadows",
                                            "shadows",      "shadows",      "refraction",
                                            "refraction",   "refraction",   "refraction"};
  const std::vector<std::string> scenes = {"torus",        "torus",        "default",
                                           "default",      "default",      "glass-sphere",
                                           "glass-sphere", "glass-sphere", "glass-sphere"};
  const std::vector<std::string> methods = {"grid",
                                            "slice-center",
                                            "reference",
                                            "voxel-center",
                                            "opaque",
                                            "reference-matched",
                                            "voxel-two-papers-smooth",
                                            "voxel-exact",
                                            "image-space"};
  const std::vector<std::string> res = {"16", "16", "", "16", "16", "", "16", "16", ""};
  const std::vector<std::string> measures = {"chamfer_rel",        "chamfer_rel",        "transmittance_rmse",
                                             "transmittance_rmse", "transmittance_rmse", "image_rmse",
                                             "image_rmse",         "image_rmse",         "image_rmse"};
  ASSERT_EQ(methods.size(), rows.size());
  const std::set<size_t> references = {2, 5};
  for (size_t i = 0; i < rows.size(); ++i) {
    const auto& row = rows[i];
    EXPECT_EQ(row.at("effect"), effects[i]);
    EXPECT_EQ(row.at("scene"), scenes[i]);
    EXPECT_EQ(row.at("method"), methods[i]);
    EXPECT_EQ(row.at("resolution"), res[i]) << methods[i];
    EXPECT_EQ(row.at("error_measure"), measures[i]);
    EXPECT_EQ(row.at("time_measure"), i < 2 ? "kernels" : "frame");
    const double t = std::stod(row.at("time_ms")), e = std::stod(row.at("error"));
    EXPECT_GT(t, 0.0) << methods[i];
    EXPECT_LE(std::stod(row.at("time_ms_min")), t) << methods[i];
    EXPECT_GE(std::stod(row.at("time_ms_max")), t) << methods[i];
    EXPECT_TRUE(std::isfinite(e)) << methods[i] << " " << row.at("error");
    EXPECT_GE(e, 0.0) << methods[i];
    EXPECT_TRUE(row.at("front") == "0" || row.at("front") == "1") << row.at("front");
    EXPECT_EQ(row.at("reference"), references.count(i) ? "1" : "0") << methods[i];
    if (references.count(i)) {
      EXPECT_EQ(e, 0.0) << methods[i];
    }
  }
  EXPECT_GT(std::stoull(rows[0].at("bytes")), 0u);
  EXPECT_GT(std::stoull(rows[6].at("bytes")), 0u);
  // The front of each (effect, scene): exactly the rows no other row of the pair beats.
  for (size_t i = 0; i < rows.size(); ++i) {
    const double ti = std::stod(rows[i].at("time_ms")), ei = std::stod(rows[i].at("error"));
    bool beaten = false;
    for (size_t j = 0; j < rows.size(); ++j) {
      if (rows[j].at("effect") != rows[i].at("effect")) continue;
      const double tj = std::stod(rows[j].at("time_ms")), ej = std::stod(rows[j].at("error"));
      beaten = beaten || (tj <= ti && ej <= ei && (tj < ti || ej < ei));
    }
    EXPECT_EQ(rows[i].at("front"), beaten ? "0" : "1") << methods[i];
  }
  // The page and one picture per effect (the charts need Debian's python3 with matplotlib).
  if (std::system("/usr/bin/python3 -c 'import matplotlib' >/dev/null 2>&1") == 0) {
    const std::string md = test::slurp(page);
    for (const std::string effect : {"voxelization", "shadows", "refraction"}) {
      EXPECT_TRUE(fs::exists(dir / "docs" / "images" / "pareto" / (effect + ".png"))) << effect;
      EXPECT_NE(md.find("](images/pareto/" + effect + ".png)"), std::string::npos) << md;
    }
    EXPECT_NE(md.find("Generated by `voxr bench pareto --out"), std::string::npos) << md;
    EXPECT_NE(md.find("### refraction: glass-sphere"), std::string::npos) << md;
    EXPECT_NE(md.find("The reference (reference-matched, "), std::string::npos) << md;
  }
}

TEST(BenchParetoCli, UnknownEffectIsAOneLineError) {
  const fs::path prefix = scratch() / "bad";
  const test::CliResult r = run_voxr("bench pareto --effects voxelisation --out " + prefix.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("unknown effect 'voxelisation'"), std::string::npos) << r.err;
  EXPECT_EQ(test::count_lines(r.err), 1) << r.err;
  EXPECT_FALSE(fs::exists(prefix.string() + ".csv"));
}

TEST(BenchParetoCli, HelpIsForwardedFromVoxr) {
  const test::CliResult r = run_voxr("bench pareto --help");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("--quick"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--doc"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace voxr
