#include "cli/bench_stability.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <filesystem>

#include "bench/report_fields.h"
#include "cl/cl_runtime.h"
#include "cli/bench_support.h"
#include "cli/commands.h"
#include "cli/option_groups.h"
#include "io/atomic_file.h"
#include "stability/stability_suite.h"
#include "util/error.h"

namespace voxr::cli {

namespace fs = std::filesystem;

namespace {

// The command line that regenerates the page (the device is the machine's, not the page's).
std::string regenerate_command(const BenchStabilityArgs& args) {
  std::string command = "voxr bench stability";
  if (args.full) command += " --full";
  for (const std::string& f : args.families) command += " --family " + f;
  command += " --doc " + args.doc;
  command += args.pictures.empty() ? " --pictures ''" : " --pictures " + args.pictures;
  return command;
}

}  // namespace

int run_bench_stability(const BenchStabilityArgs& args) {
  const std::vector<StabilityCase> all = all_stability_cases();
  for (const std::string& f : args.families)
    if (std::none_of(all.begin(), all.end(), [&](const StabilityCase& c) { return c.family == f; }))
      fail("--family: no case of family '{}' (families: voxelization, rendering, temporal, inputs)", f);
  ClRuntime cl(args.device);
  const std::array<double, 3> load_before = load_averages();
  StabilityContext ctx{cl, args.full, {}, {}};
  ctx.progress = [](const std::string& line) {
    fmt::print("{}\n", line);
    std::fflush(stdout);
  };
  const std::string device = fmt::format("{} ({}, driver {})", cl.device().name, cl.device().platform_name,
                                         cl.device().driver_version);
  fmt::print("device: {}\n", device);
  std::vector<StabilityCase> cases;
  for (const StabilityCase& c : all)
    if (args.families.empty() ||
        std::find(args.families.begin(), args.families.end(), c.family) != args.families.end())
      cases.push_back(c);
  if (!args.pictures.empty()) {
    ctx.picture_dir = args.pictures;
    // The folder holds the suite's pictures only: stale ones of renamed cases go (once every argument has
    // been checked and the device is open).
    if (fs::is_directory(ctx.picture_dir))
      for (const fs::directory_entry& e : fs::directory_iterator(ctx.picture_dir))
        if (e.is_regular_file() && e.path().extension() == ".png") fs::remove(e.path());
  }
  const std::vector<StabilityCaseResult> results = run_stability_cases(cases, ctx);
  const std::array<double, 3> load_after = load_averages();
  StabilityHeader header;
  header.command = regenerate_command(args);
  header.device = device;
  header.date = utc_now();
  header.load = fmt::format("{:.2f} {:.2f} {:.2f} before, {:.2f} {:.2f} {:.2f} after", load_before[0],
                            load_before[1], load_before[2], load_after[0], load_after[1], load_after[2]);
  const fs::path doc(args.doc);
  const fs::path doc_dir = doc.parent_path().empty() ? fs::path(".") : doc.parent_path();
  const std::string link = args.pictures.empty()
                               ? std::string(".")
                               : fs::weakly_canonical(fs::absolute(args.pictures))
                                     .lexically_relative(fs::weakly_canonical(fs::absolute(doc_dir)))
                                     .generic_string();
  if (!doc.parent_path().empty()) fs::create_directories(doc.parent_path());
  write_file_atomically(doc, stability_markdown(results, header, link));
  fmt::print("wrote {}\n", args.doc);
  const std::vector<std::string> failures = stability_failures(results);
  if (failures.empty()) return 0;
  fmt::print(stderr, "voxr: {} stability rows break their bounds:\n", failures.size());
  for (const std::string& line : failures) fmt::print(stderr, "  {}\n", line);
  return 1;
}

Command add_bench_stability(CLI::App& bench) {
  auto args = std::make_shared<BenchStabilityArgs>();
  CLI::App* sub = bench.add_subcommand(
      "stability",
      "The stability suite: every method on every failure mode, bounds checked -> docs/stability.md");
  sub->add_flag("--full", args->full, "the full cases (default: the small versions the tests run)");
  sub->add_option("--family", args->families,
                  "run these families only (voxelization, rendering, temporal, inputs)")
      ->delimiter(',');
  sub->add_option("--doc", args->doc, "the Markdown page to write")->capture_default_str();
  sub->add_option("--pictures", args->pictures, "folder of the page's pictures ('' for none)")
      ->capture_default_str();
  add_device_option(*sub, args->device);
  return {sub, [args] { return run_bench_stability(*args); }};
}

}  // namespace voxr::cli
