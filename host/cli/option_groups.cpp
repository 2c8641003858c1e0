#include "cli/option_groups.h"

#include "cli/parse_args.h"
#include "core/grid_spec.h"
#include "util/error.h"

namespace voxr::cli {

namespace {

struct GridKindInfo {
  uint32_t lo, hi;
  const char* help;
};

GridKindInfo grid_kind_info(GridKind kind) {
  switch (kind) {
    case GridKind::kVoxel:
      return {1u, kMaxGridDim, "voxels along the longest axis of the scene bounds"};
    case GridKind::kShadow:
      return {kShadowResMin, kShadowResMax,
              "shadow grid of the voxel, uniform, filter and opaque methods: columns along the longer side "
              "of the light's grid, and as many slabs; voxel-exact: voxels of its triangle grid along the "
              "scene's longest side (a speed knob: the result is exact at any)"};
    case GridKind::kRefraction:
      return {kRefractionResMin, kRefractionResMax,
              "voxel refraction grid: voxels along the longest side of the fine grid (--refraction-grid "
              "fitted: the dielectrics and 2 voxels of margin; scene: the whole scene); voxel-exact: of the "
              "scene's grid of triangle lists, up to 2000, a speed knob only (256 was the fastest of 64, 128 "
              "and 256)"};
  }
  throw InternalError("unknown GridKind");
}

}  // namespace

CLI::Option* add_device_option(CLI::App& app, std::string& device) {
  return app.add_option("--device", device,
                        "OpenCL device: P:D as `voxr devices` lists them, or a name substring (default: "
                        "$VOXR_DEVICE, else the first GPU, else the first CPU)");
}

CLI::Option* add_size_option(CLI::App& app, std::string& size) {
  return app
      .add_option("--size", size, "image WIDTHxHEIGHT, e.g. 640x480 (each side a whole number in 1..16384)")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            try {
              parse_size(text, "--size");
              return "";
            } catch (const Error& e) {
              // parse_size's message starts "--size '...'"; CLI11 puts "--size: " before the one returned.
              const std::string message = e.what(), flag = "--size ";
              return message.starts_with(flag) ? message.substr(flag.size()) : message;
            }
          },
          "WIDTHxHEIGHT"));
}

CLI::Option* add_repeat_option(CLI::App& app, int& repeat) {
  return app.add_option("--repeat", repeat, "timed runs (frames) per case, the median reported")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
}

CLI::Option* add_warmup_option(CLI::App& app, int& warmup) {
  return app.add_option("--warmup", warmup, "untimed runs (frames) per case before the timed ones")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
}

void add_repeat_options(CLI::App& app, int& repeat, int& warmup) {
  add_repeat_option(app, repeat);
  add_warmup_option(app, warmup);
}

CLI::Option* add_fresh_option(CLI::App& app, int& fresh, const std::string& process) {
  return app
      .add_option("--fresh", fresh,
                  "fresh processes per case, each `" + process + "` timed from start to exit (0: none)")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
}

CLI::Option* add_out_prefix_option(CLI::App& app, std::string& out, const std::string& files) {
  return app.add_option("--out", out, "output prefix: " + files)->capture_default_str();
}

void add_report_options(CLI::App& app, std::string& report, bool& profile, bool& quiet,
                        const std::string& contents) {
  app.add_option("--report", report, "write a JSON report: " + contents);
  app.add_flag("--profile", profile, "print a per-kernel time table");
  app.add_flag("-q,--quiet", quiet, "print nothing but errors");
}

CLI::Option* add_grid_option(CLI::App& app, const std::string& name, GridKind kind, uint32_t& res) {
  const GridKindInfo info = grid_kind_info(kind);
  return app.add_option(name, res, info.help)->check(CLI::Range(info.lo, info.hi));
}

CLI::Option* add_grid_option(CLI::App& app, const std::string& name, GridKind kind,
                             std::vector<uint32_t>& res) {
  const GridKindInfo info = grid_kind_info(kind);
  return app.add_option(name, res, std::string(info.help) + " (comma list)")
      ->delimiter(',')
      ->check(CLI::Range(info.lo, info.hi))
      ->capture_default_str();
}

}  // namespace voxr::cli
