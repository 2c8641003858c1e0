// The voxr executable's exit codes (host/cli/main.cpp): 0 success, --help and --version; 2 usage errors
// found while parsing the command line, on one line with a pointer to --help; 1 every other failure.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <string>

#include "cli_support.h"
#include "test_support.h"

namespace voxr {
namespace {

namespace fs = std::filesystem;

using Result = test::CliResult;

Result run(const std::string& args) {
  return test::run_voxr(args);
}

int lines(const std::string& text) {
  return test::count_lines(text);
}

// Exit 2, one line naming `needle` and pointing at `help` ("voxr voxelize --help").
void expect_usage_error(const std::string& args, const std::string& needle, const std::string& help) {
  SCOPED_TRACE("voxr " + args);
  const Result r = run(args);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'" + help + "'"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.rfind("voxr: error: ", 0), 0u) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST(ExitCode, UnknownFlagIsAUsageError) {
  expect_usage_error("voxelize --no-such-flag", "--no-such-flag", "voxr voxelize --help");
  expect_usage_error("--no-such-flag", "--no-such-flag", "voxr --help");
}

TEST(ExitCode, BadValueIsAUsageError) {
  expect_usage_error("voxelize --res abc", "abc", "voxr voxelize --help");
  expect_usage_error("voxelize --res 0", "--res", "voxr voxelize --help");
  expect_usage_error("bench table1 --repeat 0", "--repeat", "voxr bench table1 --help");
}

TEST(ExitCode, MissingArgumentIsAUsageError) {
  expect_usage_error("voxelize --res", "--res", "voxr voxelize --help");
  expect_usage_error("voxelize -o", "--output", "voxr voxelize --help");
  expect_usage_error("bench", "subcommand", "voxr bench --help");
}

TEST(ExitCode, MissingOrUnknownSubcommandIsAUsageError) {
  expect_usage_error("", "subcommand", "voxr --help");
  expect_usage_error("voxelise", "voxelise", "voxr --help");
}

TEST(ExitCode, HelpAndVersionSucceed) {
  for (const char* args : {"--help", "voxelize --help", "bench table1 --help", "--version"}) {
    SCOPED_TRACE(args);
    const Result r = run(args);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_FALSE(r.out.empty());
    EXPECT_TRUE(r.err.empty()) << r.err;
  }
  EXPECT_NE(run("voxelize --help").out.find("--res"), std::string::npos);
  EXPECT_NE(run("--version").out.find("voxr"), std::string::npos);
}

TEST(ExitCode, FailuresAfterParsingExitOne) {
  const test::TempDir dir;
  const fs::path missing = dir.path() / "missing.obj";
  const fs::path bad = dir.write("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
  for (const fs::path& input : {missing, bad}) {
    SCOPED_TRACE(input.string());
    const Result r = run("voxelize " + input.string() + " --res 8");
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find(input.string()), std::string::npos) << r.err;
    EXPECT_EQ(lines(r.err), 1) << r.err;
    EXPECT_EQ(r.err.find("--help"), std::string::npos) << "not a usage error: " << r.err;
  }
}

TEST(ExitCode, SuccessIsZero) {
  const test::TempDir dir;
  const fs::path mesh =
      dir.write("tetra.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  const Result r = run("voxelize " + mesh.string() + " --res 8 -q");
  EXPECT_EQ(r.code, 0) << r.err;
}

}  // namespace
}  // namespace voxr
