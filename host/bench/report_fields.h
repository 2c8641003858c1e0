// What every benchmark's report records besides its measurements: the machine's load, the time and a scene's
// label (the drivers in this folder and the CLI's bench commands).
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace voxr {

// /proc/loadavg's 1, 5 and 15 minute averages; -1 where it cannot be read.
std::array<double, 3> load_averages();

// The three load averages as "1.23 0.98 0.75" (Markdown and CSV cells).
std::string load_average_text();

// The current time as "2026-11-30 18:40:00 UTC".
std::string utc_now();

// A scene's label in tables: "default" for the built-in scene, else the file's stem.
std::string scene_label(const std::string& scene);

// `v` with `digits` decimals; "nan", "inf", "-inf" for those (a PSNR of equal images is inf).
std::string number_cell(double v, int digits);

// A grid resolution's cell: empty for 0 (a method without a grid).
std::string resolution_cell(uint32_t resolution);

}  // namespace voxr
