#include "cli/bench_support.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "bench/median.h"
#include "cli/process.h"
#include "core/clock.h"
#include "core/error.h"

namespace voxr::cli {

namespace fs = std::filesystem;

std::array<double, 3> load_averages() {
  std::array<double, 3> load = {-1.0, -1.0, -1.0};
  std::ifstream in("/proc/loadavg");
  in >> load[0] >> load[1] >> load[2];
  return load;
}

std::string scene_label(const std::string& scene) {
  return scene == "default" ? "default" : fs::path(scene).stem().string();
}

std::vector<double> time_fresh_renders(const std::vector<std::string>& render_args, int count,
                                       const std::string& device, const std::string& tag) {
  const fs::path image = fs::temp_directory_path() / fmt::format("voxr-{}-{}.png", tag, ::getpid());
  std::vector<std::string> argv = {executable_path().string(), "render"};
  argv.insert(argv.end(), render_args.begin(), render_args.end());
  for (const char* a : {"-q", "-o"}) argv.push_back(a);
  argv.push_back(image.string());
  if (!device.empty()) {
    argv.push_back("--device");
    argv.push_back(device);
  }
  std::vector<double> wall;
  for (int r = 0; r < count; ++r) {
    const auto start = Clock::now();
    if (run_program(argv) != 0) fail("the fresh process `voxr render` failed (see above)");
    wall.push_back(ms_since(start));
  }
  std::error_code ec;
  fs::remove(image, ec);
  return wall;
}

std::string fresh_table_row(const std::string& label, uint64_t triangles,
                            const std::vector<double>& wall_ms) {
  return fmt::format("| {} | {} | {:.0f} | {:.0f} | {:.0f} |\n", label, triangles, median(wall_ms),
                     *std::min_element(wall_ms.begin(), wall_ms.end()),
                     *std::max_element(wall_ms.begin(), wall_ms.end()));
}

}  // namespace voxr::cli
