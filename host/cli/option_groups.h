// Flags that several subcommands take, each declared once here: the same name, help text and check wherever
// it appears (docs/cli.md lists them with the subcommands that take them). A subcommand's options struct
// holds the values, one line per flag in its add_* function; these functions only register the flags.
//
// Checks run while CLI11 parses, so a bad value is a usage error (exit 2) on one line naming the flag and
// the value, before anything runs: "--size: '0x5': width and height must be whole numbers in 1..16384".
// The rendering groups (they read the render library's method tables) are in option_groups_render.h.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace voxr::cli {

// --device: OpenCL device P:D or a name substring. An unknown device fails when the runtime opens (voxelize
// and render open it on a second thread while the input is read), with select_device's one-line message.
CLI::Option* add_device_option(CLI::App& app, std::string& device);

// --size WIDTHxHEIGHT (parse_size), checked while parsing.
CLI::Option* add_size_option(CLI::App& app, std::string& size);

// --repeat N (1..1000): timed runs per case, the median reported.
CLI::Option* add_repeat_option(CLI::App& app, int& repeat);
// --warmup N (0..100): untimed runs before the timed ones.
CLI::Option* add_warmup_option(CLI::App& app, int& warmup);
// Both of the above.
void add_repeat_options(CLI::App& app, int& repeat, int& warmup);

// --fresh N (0..1000): `process` (e.g. "voxr render --frames N") started as a new process N times per case
// and timed from outside; 0 starts none.
CLI::Option* add_fresh_option(CLI::App& app, int& fresh, const std::string& process);

// --out PREFIX of a benchmark's files; `files` names them ("PREFIX.csv and PREFIX.md").
CLI::Option* add_out_prefix_option(CLI::App& app, std::string& out, const std::string& files);

// --report FILE (a JSON report holding `contents`), --profile and -q/--quiet: voxelize and render.
void add_report_options(CLI::App& app, std::string& report, bool& profile, bool& quiet,
                        const std::string& contents);

// The grids a resolution flag sizes; each kind has one range and one meaning wherever its flag appears.
enum class GridKind {
  kVoxel,       // a voxelization grid: 1..kMaxGridDim voxels along the scene's longest axis
  kShadow,      // the light's grid: 3..4096 columns along its longer side, and as many slabs
  kRefraction,  // the voxel refraction grid: 2..4096 voxels along the scene's longest side
};
inline constexpr uint32_t kShadowResMin = 3, kShadowResMax = 4096;
inline constexpr uint32_t kRefractionResMin = 2, kRefractionResMax = 4096;

// A flag `name` (e.g. "--res", "--shadow-res", "--vox-res") taking one resolution of `kind`, or a comma list.
CLI::Option* add_grid_option(CLI::App& app, const std::string& name, GridKind kind, uint32_t& res);
CLI::Option* add_grid_option(CLI::App& app, const std::string& name, GridKind kind,
                             std::vector<uint32_t>& res);

}  // namespace voxr::cli
