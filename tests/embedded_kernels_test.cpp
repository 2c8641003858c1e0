// The embedded kernel tables (cmake/embed_kernels.cmake, cl/embedded_kernels.h): every source under kernels/
// is in exactly one table under its file name, the test kernels only in the table the shipped programs do
// not link, and the embed step stops the build on two files of one name or a file outside the stage folders.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>

#include "cl/embedded_kernels.h"
#include "cli_support.h"
#include "test_support.h"

namespace voxr {
namespace {

namespace fs = std::filesystem;

std::map<std::string, std::string> table_map(const std::vector<EmbeddedKernel>& table) {
  std::map<std::string, std::string> out;
  for (const EmbeddedKernel& k : table) out.emplace(k.name, k.source);
  return out;
}

TEST(EmbeddedKernels, EverySourceIsInOneTableByFileName) {
  const std::map<std::string, std::string> shipped = table_map(embedded_kernels());
  const std::map<std::string, std::string> tests = table_map(embedded_test_kernels());
  size_t files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(VOXR_SOURCE_DIR) / "kernels")) {
    const fs::path& p = entry.path();
    if (!entry.is_regular_file() || (p.extension() != ".cl" && p.extension() != ".h")) continue;
    ++files;
    const std::string name = p.filename().string();
    const bool test_kernel = p.parent_path().filename() == "test";
    const auto& mine = test_kernel ? tests : shipped;
    const auto& other = test_kernel ? shipped : tests;
    ASSERT_TRUE(mine.count(name)) << p;
    EXPECT_EQ(mine.at(name), test::slurp(p)) << p;
    EXPECT_FALSE(other.count(name)) << p;
    ASSERT_NE(find_embedded_kernel(name), nullptr) << name;
    EXPECT_EQ(find_embedded_kernel(name)->source, mine.at(name));
  }
  EXPECT_EQ(shipped.size() + tests.size(), files);
  EXPECT_TRUE(tests.count("layout_probe.cl") && tests.count("grid_view_probe.cl"));
  EXPECT_EQ(find_embedded_kernel("no_such_kernel.cl"), nullptr);
}

TEST(EmbeddedKernels, ShippedProgramHoldsNoTestKernel) {
  const std::string binary = test::slurp(VOXR_CLI_PATH);
  ASSERT_FALSE(binary.empty());
  EXPECT_NE(binary.find("vox_raster.cl"), std::string::npos);
  for (const EmbeddedKernel& k : embedded_test_kernels())
    EXPECT_EQ(binary.find(std::string(k.name)), std::string::npos) << k.name;
}

// Runs the embed script over `dir`; returns its exit status and what it printed.
std::pair<int, std::string> embed(const fs::path& dir) {
  const fs::path log = dir / "embed.log";
  const std::string cmd = std::string(VOXR_CMAKE_COMMAND) + " -DKERNEL_DIR=" + (dir / "kernels").string() +
                          " -DOUT=" + (dir / "shipped.cpp").string() +
                          " -DTEST_OUT=" + (dir / "test.cpp").string() + " -P " + VOXR_SOURCE_DIR +
                          "/cmake/embed_kernels.cmake >" + log.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, test::slurp(log)};
}

TEST(EmbeddedKernels, EmbedStepRefusesSharedFileNamesAndLooseFiles) {
  test::TempDir dir;
  dir.write("kernels/common/a.h", "/* a */");
  dir.write("kernels/util/b.cl", "/* b */");
  dir.write("kernels/test/c.cl", "/* c */");
  const auto [ok, ok_log] = embed(dir.path());
  ASSERT_EQ(ok, 0) << ok_log;
  const std::string shipped = test::slurp(dir.path() / "shipped.cpp"),
                    tests = test::slurp(dir.path() / "test.cpp");
  EXPECT_NE(shipped.find("{\"b.cl\""), std::string::npos) << shipped;
  EXPECT_EQ(shipped.find("c.cl"), std::string::npos) << shipped;
  EXPECT_NE(tests.find("{\"c.cl\""), std::string::npos) << tests;

  dir.write("kernels/render/b.cl", "/* another b */");
  const auto [shared, shared_log] = embed(dir.path());
  EXPECT_NE(shared, 0);
  EXPECT_NE(shared_log.find("kernels/render/b.cl and kernels/util/b.cl share the file name b.cl"),
            std::string::npos)
      << shared_log;

  fs::remove(dir.path() / "kernels/render/b.cl");
  dir.write("kernels/loose.cl", "/* d */");
  const auto [loose, loose_log] = embed(dir.path());
  EXPECT_NE(loose, 0);
  EXPECT_NE(loose_log.find("kernels/loose.cl lies outside the stage folders"), std::string::npos)
      << loose_log;
}

}  // namespace
}  // namespace voxr
