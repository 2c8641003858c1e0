// voxr command line: one options struct and one file per subcommand (host/cli/cmd_*.cpp).
//
// Exit codes, decided here and nowhere else: 0 success (and --help, --version); 2 a usage error found while
// parsing the command line (unknown flag or subcommand, missing or malformed value, value out of range);
// 1 every other failure (voxr::Error: bad or missing files, meshes, outputs, devices; out of memory;
// internal errors, which also ask to be reported).
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <cstdio>
#include <string>

#include "cli/commands.h"
#include "cli/process.h"
#include "util/error.h"

namespace {

constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;

// The deepest subcommand the parse reached (the root when none).
const CLI::App& reached(const CLI::App& app) {
  const CLI::App* at = &app;
  while (!at->get_subcommands().empty()) at = at->get_subcommands().front();
  return *at;
}

// "voxr bench table1": the reached subcommand's path, so the hint names the right --help.
std::string command_path(const CLI::App& app) {
  std::string path;
  for (const CLI::App* at = &app; at; at = at->get_parent())
    path = (at->get_parent() ? at->get_name() : "voxr") + (path.empty() ? "" : " " + path);
  return path;
}

// --help and --version print and exit 0; every other parse or validation error prints CLI11's message and
// a hint on one line and exits 2.
int parse_error_exit(const CLI::App& app, const CLI::ParseError& e) {
  if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) {
    app.exit(e);
    return 0;
  }
  const CLI::App& at = reached(app);
  std::string message = e.what();
  // CLI11 checks "a subcommand is required" before unexpected arguments: "voxr voxelise" and
  // "voxr --frobnicate" would only say that a subcommand is required. Name the culprit instead.
  const std::vector<std::string> extra = app.remaining(true);
  if (e.get_name() == "RequiredError" && at.get_require_subcommand_min() > 0 &&
      at.get_subcommands().empty() && !extra.empty())
    message = fmt::format("unknown {} '{}'", extra[0].starts_with('-') ? "flag" : "subcommand", extra[0]);
  while (!message.empty() && message.back() == '\n') message.pop_back();
  for (char& c : message)
    if (c == '\n') c = ' ';
  fmt::print(stderr, "voxr: error: {} (see '{} --help')\n", message, command_path(at));
  return kExitUsage;
}

// Rendering links Embree (and TBB) and the image libraries: once OpenImageIO's ~250 shared libraries, now
// ~20 that load in under 10 ms. `voxr` still forwards the rendering commands to `voxr-render`
// beside it (the same CLI built with them: VOXR_CLI_RENDER) by exec, before any parsing.
#ifndef VOXR_CLI_RENDER
bool renders(int argc, char** argv) {
  const std::string first = argc > 1 ? argv[1] : "", second = argc > 2 ? argv[2] : "";
  return first == "render" ||
         (first == "bench" && (second == "shadows" || second == "refraction" || second == "stability" ||
                               second == "animation" || second == "pareto"));
}
#endif

int run(int argc, char** argv) {
#ifndef VOXR_CLI_RENDER
  if (renders(argc, argv))
    voxr::cli::exec_program(voxr::cli::executable_folder() / "voxr-render", argc, argv);
#endif
  CLI::App app{"voxr: voxelize triangle scenes with OpenCL kernels and render effects from the voxels"};
  app.name("voxr");  // voxr-render too: its messages and usage speak of the command the user typed
  app.require_subcommand(1);
  app.set_version_flag("--version", "voxr 0.1.0");
  const voxr::cli::Command commands[] = {voxr::cli::add_devices(app), voxr::cli::add_voxelize(app),
                                         voxr::cli::add_render(app), voxr::cli::add_bench(app)};
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return parse_error_exit(app, e);
  }
  for (const voxr::cli::Command& command : commands)
    if (command.app->parsed()) return command.run();
  throw voxr::InternalError("no subcommand to run after a successful parse");
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const voxr::Error& e) {
    fmt::print(stderr, "voxr: error: {}\n", e.what());
  } catch (const voxr::InternalError& e) {
    fmt::print(stderr, "voxr: internal error (please report): {}\n", e.what());
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "voxr: error: out of host memory; use a smaller grid (--res) or fewer channels\n");
  } catch (const std::exception& e) {
    fmt::print(stderr, "voxr: error: {}\n", e.what());
  } catch (...) {
    fmt::print(stderr, "voxr: error: unknown failure\n");
  }
  return kExitFailure;
}
