#include "bench/report_fields.h"

#include <fmt/format.h>

#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>

namespace voxr {

std::array<double, 3> load_averages() {
  std::array<double, 3> load = {-1.0, -1.0, -1.0};
  std::ifstream in("/proc/loadavg");
  in >> load[0] >> load[1] >> load[2];
  return load;
}

std::string load_average_text() {
  const std::array<double, 3> load = load_averages();
  return fmt::format("{:.2f} {:.2f} {:.2f}", load[0], load[1], load[2]);
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char text[64];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&t));
  return text;
}

std::string scene_label(const std::string& scene) {
  return scene == "default" ? "default" : std::filesystem::path(scene).stem().string();
}

std::string number_cell(double v, int digits) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format("{:.{}f}", v, digits);
}

std::string resolution_cell(uint32_t resolution) {
  return resolution ? std::to_string(resolution) : "";
}

}  // namespace voxr
