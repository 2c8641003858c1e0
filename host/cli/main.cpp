// voxr command line: one options struct and one file per subcommand (host/cli/cmd_*.cpp).
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <cstdio>

#include "cli/commands.h"
#include "core/error.h"

int main(int argc, char** argv) {
  CLI::App app{"voxr: voxelize triangle scenes with OpenCL kernels and render effects from the voxels"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "voxr 0.1.0");
  // One line per failure: "voxr: error: --res: Value 0 not in range 1 to 16384".
  app.failure_message(
      [](const CLI::App*, const CLI::Error& e) { return fmt::format("voxr: error: {}\n", e.what()); });
  const voxr::cli::Command commands[] = {voxr::cli::add_devices(app), voxr::cli::add_voxelize(app),
                                         voxr::cli::add_bench(app)};
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    for (const voxr::cli::Command& command : commands)
      if (command.app->parsed()) return command.run();
    return 2;
  } catch (const voxr::Error& e) {
    fmt::print(stderr, "voxr: error: {}\n", e.what());
    return 1;
  } catch (const voxr::InternalError& e) {
    fmt::print(stderr, "voxr: internal error (please report): {}\n", e.what());
    return 3;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "voxr: error: out of host memory; use a smaller grid (--res) or fewer channels\n");
    return 1;
  } catch (const std::exception& e) {
    fmt::print(stderr, "voxr: error: {}\n", e.what());
    return 1;
  }
}
