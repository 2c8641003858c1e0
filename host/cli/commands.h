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
// `voxr bench shadows`, a subcommand of `bench`.
Command add_bench_shadows(CLI::App& bench);
// `voxr bench refraction`, a subcommand of `bench`.
Command add_bench_refraction(CLI::App& bench);
// `voxr bench stability`, a subcommand of `bench`.
Command add_bench_stability(CLI::App& bench);
// `voxr bench animation`, a subcommand of `bench`.
Command add_bench_animation(CLI::App& bench);
// `voxr bench pareto`, a subcommand of `bench`.
Command add_bench_pareto(CLI::App& bench);
// voxr-render holds render and bench shadows, refraction, stability, animation and pareto (VOXR_CLI_RENDER);
// voxr forwards them to it (main.cpp) and registers them only for --help (render_forward.cpp).

}  // namespace voxr::cli
