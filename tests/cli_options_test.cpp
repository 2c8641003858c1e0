// The flags several subcommands share (host/cli/option_groups.h) are one flag each: the same help text in
// every subcommand's --help, and the same one-line refusal of a bad value from every subcommand that takes
// it.
#include <gtest/gtest.h>

#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.h"

namespace voxr {
namespace {

namespace fs = std::filesystem;
using test::run_voxr;
using test::scratch;

const std::string kSphere = std::string(VOXR_SOURCE_DIR) + "/data/scenes/glass-sphere.json";

// CLI11 prints an option as "  NAMES TYPE=DEFAULT ..." padded to this column, then its description (on the
// next line, at the same column, when the names and type are longer).
constexpr size_t kHelpColumn = 30;

// `flag`'s entry in `voxr COMMAND --help`, the default value and list marks taken out (they differ by
// design: 640x480 here, 320x240 there; one resolution or a comma list): "TYPE | description".
std::string help_entry(const std::string& command, const std::string& flag) {
  const test::CliResult r = run_voxr(command + " --help");
  EXPECT_EQ(r.code, 0) << command << ": " << r.err;
  std::istringstream in(r.out);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    if (!line.starts_with("  " + flag + " ") && !line.starts_with("  " + flag + ",")) continue;
    std::string head = line, description;
    if (i + 1 < lines.size() && lines[i + 1].starts_with(std::string(kHelpColumn, ' '))) {
      description = lines[i + 1].substr(kHelpColumn);
    } else if (line.size() > kHelpColumn) {
      head = line.substr(0, kHelpColumn);
      description = line.substr(kHelpColumn);
    }
    head = std::regex_replace(head, std::regex(R"(\s+$)"), "");
    head = std::regex_replace(head, std::regex(R"( \.\.\.$)"), "");
    head = std::regex_replace(head, std::regex("=.*$"), "");  // the default
    description = std::regex_replace(description, std::regex(R"( \(comma list\))"), "");
    description = std::regex_replace(description, std::regex("`[^`]*`"), "`PROCESS`");  // --fresh's process
    return head + " | " + description;
  }
  ADD_FAILURE() << "voxr " << command << " --help has no " << flag << ":\n" << r.out;
  return "";
}

struct Shared {
  std::string flag;
  std::vector<std::string> commands;  // every subcommand that takes it
};

const std::vector<Shared> kShared = {
    {"--device",
     {"voxelize", "render", "bench voxelize", "bench table1", "bench solid", "bench shadows",
      "bench refraction", "bench stability", "bench animation", "bench pareto"}},
    {"--size", {"render", "bench shadows", "bench refraction", "bench animation", "bench pareto"}},
    {"--repeat",
     {"bench voxelize", "bench table1", "bench solid", "bench shadows", "bench refraction", "bench pareto"}},
    {"--warmup", {"bench voxelize", "bench table1", "bench shadows", "bench refraction", "bench pareto"}},
    {"--fresh", {"bench voxelize", "bench shadows", "bench refraction", "bench animation"}},
    {"--profile", {"voxelize", "render"}},
    {"-q", {"voxelize", "render"}},
    {"--res", {"voxelize", "bench voxelize", "bench table1", "bench solid"}},  // voxel grids
    {"--res", {"render", "bench refraction"}},                                 // refraction grids
    {"--shadow-res", {"render", "bench refraction", "bench pareto"}},
};

TEST(CliOptions, SharedFlagsHaveOneHelpText) {
  for (const Shared& s : kShared) {
    const std::string first = help_entry(s.commands[0], s.flag);
    EXPECT_NE(first.find(" | "), std::string::npos) << s.flag;
    for (size_t c = 1; c < s.commands.size(); ++c)
      EXPECT_EQ(help_entry(s.commands[c], s.flag), first)
          << s.flag << ": voxr " << s.commands[c] << " against voxr " << s.commands[0];
  }
}

struct Refusal {
  std::string value;  // "--size 0x5"
  std::vector<std::string> commands;
  std::string message;  // after "voxr: error: "
};

TEST(CliOptions, SharedFlagsRefuseABadValueWithOneMessage) {
  for (const Refusal& r : std::vector<Refusal>{
           {"--size 0x5",
            {"render", "bench shadows", "bench refraction", "bench animation", "bench pareto"},
            "--size: '0x5': width and height must be whole numbers in 1..16384"},
           {"--size 640",
            {"render", "bench shadows", "bench refraction", "bench animation", "bench pareto"},
            "--size: '640': expected WIDTHxHEIGHT, e.g. 640x480"},
           {"--size 64xabc",
            {"render", "bench shadows", "bench refraction", "bench animation", "bench pareto"},
            "--size: '64xabc': expected WIDTHxHEIGHT, e.g. 640x480"},
           {"--repeat 0",
            {"bench voxelize", "bench table1", "bench solid", "bench shadows", "bench refraction",
             "bench pareto"},
            "--repeat: Value 0 not in range 1 to 1000"},
           {"--warmup 101",
            {"bench voxelize", "bench table1", "bench shadows", "bench refraction", "bench pareto"},
            "--warmup: Value 101 not in range 0 to 100"},
           {"--fresh 1001",
            {"bench voxelize", "bench shadows", "bench refraction", "bench animation"},
            "--fresh: Value 1001 not in range 0 to 1000"},
           {"--res 0",
            {"voxelize", "bench voxelize", "bench table1", "bench solid"},
            "--res: Value 0 not in range 1 to 16384"},
           {"--res 1", {"render", "bench refraction"}, "--res: Value 1 not in range 2 to 4096"},
           {"--shadow-res 2",
            {"render", "bench refraction", "bench pareto"},
            "--shadow-res: Value 2 not in range 3 to 4096"},
           {"--shadows soft",
            {"render", "bench refraction"},
            "--shadows: unknown shadow method 'soft' (known: voxel, uniform, filter, opaque, voxel-exact, "
            "reference, none)"},
       }) {
    for (const std::string& command : r.commands) {
      SCOPED_TRACE("voxr " + command + " " + r.value);
      const test::CliResult result = run_voxr(command + " " + r.value);
      EXPECT_EQ(result.code, 2);
      EXPECT_EQ(result.err, "voxr: error: " + r.message + " (see 'voxr " + command + " --help')\n");
      EXPECT_TRUE(result.out.empty()) << result.out;
    }
  }
}

// An unknown device is found when the runtime opens (on a second thread in voxelize and render): the same
// line from every subcommand, before any work or output.
TEST(CliOptions, UnknownDeviceIsTheSameOneLineErrorEverywhere) {
  const std::string out = (scratch() / "nodevice").string();
  const std::vector<std::string> commands = {
      "voxelize --res 8 -o " + out + ".nrrd",
      "render --size 16x12 -o " + out + ".png",
      "bench voxelize --meshes torus --res 8 --fresh 0 --out " + out + ".csv",
      "bench table1 --out " + out,
      "bench solid --out " + out,
      "bench shadows --scenes default --out " + out,
      "bench refraction --scenes " + kSphere + " --out " + out,
      "bench stability --family inputs --doc " + out + ".md --pictures " + out,
      "bench animation --out " + out,
      "bench pareto --effects shadows --shadow-scenes default --out " + out,
  };
  std::string first;
  for (const std::string& command : commands) {
    SCOPED_TRACE("voxr " + command);
    const test::CliResult r = run_voxr(command + " --device 9:9");
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err.rfind("voxr: error: --device '9:9': no OpenCL device matches (devices: ", 0), 0u)
        << r.err;
    EXPECT_EQ(test::count_lines(r.err), 1) << r.err;
    if (first.empty()) first = r.err;
    EXPECT_EQ(r.err, first);
  }
  for (const char* ext : {".nrrd", ".png", ".csv", ".md"}) EXPECT_FALSE(fs::exists(out + ext)) << ext;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace voxr
