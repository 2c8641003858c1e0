// Subcommands of the voxr CLI. Each add_* registers its flags (one options struct per subcommand, owned
// by the returned closure) and returns how to run it once parsed.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>

namespace voxr::cli {

struct Command {
  CLI::App* app;
  std::function<int()> run;
};

Command add_devices(CLI::App& app);
Command add_voxelize(CLI::App& app);
Command add_bench(CLI::App& app);
Command add_render(CLI::App& app);

}  // namespace voxr::cli
