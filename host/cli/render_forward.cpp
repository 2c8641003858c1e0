// What `voxr` (without VOXR_CLI_RENDER) registers for the rendering commands: their names and summaries for
// --help. main.cpp hands every `voxr render` and `voxr bench shadows|refraction|stability|animation|pareto`
// to voxr-render before parsing, so these are never run.
#include "cli/commands.h"
#include "util/error.h"

namespace voxr::cli {

namespace {

int forwarded() {
  throw InternalError("a rendering command reached voxr instead of voxr-render");
}

}  // namespace

Command add_render(CLI::App& app) {
  CLI::App* sub = app.add_subcommand("render", "Render a scene with transparent shadows (.png or .exr)");
  sub->allow_extras();
  return {sub, forwarded};
}

Command add_bench_shadows(CLI::App& bench) {
  CLI::App* sub = bench.add_subcommand(
      "shadows", "Shadow methods x shadow resolutions x scenes: frame time against error vs Embree");
  sub->allow_extras();
  return {sub, forwarded};
}

Command add_bench_refraction(CLI::App& bench) {
  CLI::App* sub = bench.add_subcommand(
      "refraction",
      "Refraction methods x grid resolutions x scenes: frame time against error vs the matched reference");
  sub->allow_extras();
  return {sub, forwarded};
}

Command add_bench_stability(CLI::App& bench) {
  CLI::App* sub = bench.add_subcommand(
      "stability",
      "The stability suite: every method on every failure mode, bounds checked -> docs/stability.md");
  sub->allow_extras();
  return {sub, forwarded};
}

Command add_bench_animation(CLI::App& bench) {
  CLI::App* sub = bench.add_subcommand(
      "animation", "Deforming scenes re-voxelized every frame: frame rate, per-stage times, fresh process");
  sub->allow_extras();
  return {sub, forwarded};
}

Command add_bench_pareto(CLI::App& bench) {
  CLI::App* sub = bench.add_subcommand(
      "pareto",
      "Speed against accuracy: every voxelization, shadow and refraction method x resolution, the "
      "Pareto fronts, charts and a page");
  sub->allow_extras();
  return {sub, forwarded};
}

}  // namespace voxr::cli
