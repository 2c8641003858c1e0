#include "cli/bench_support.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "cli/process.h"
#include "util/clock.h"
#include "util/error.h"
#include "util/median.h"

namespace voxr::cli {

namespace fs = std::filesystem;

std::string command_line() {
  std::ifstream f("/proc/self/cmdline", std::ios::binary);
  std::string all((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  std::string line;
  size_t start = 0;
  bool first = true;
  while (start < all.size()) {
    size_t end = all.find('\0', start);
    if (end == std::string::npos) end = all.size();
    std::string word = all.substr(start, end - start);
    if (first) word = "voxr";  // voxr-render, or a path to it
    line += (first ? "" : " ") + word;
    first = false;
    start = end + 1;
  }
  return line;
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
