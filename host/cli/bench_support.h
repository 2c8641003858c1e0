// What the benchmark commands (bench voxelize, bench shadows, bench refraction) share: the machine's load, a
// scene's label, and fresh `voxr render` processes timed as a user runs them.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace voxr::cli {

// /proc/loadavg's 1, 5 and 15 minute averages; -1 where it cannot be read.
std::array<double, 3> load_averages();

// The three load averages as "1.23 0.98 0.75" (Markdown and CSV cells).
std::string load_average_text();

// The process's own command line as the user typed it, the program named "voxr" (voxr-render's argv is
// voxr's, exec'd).
std::string command_line();

// The current time as "2026-11-30 18:40:00 UTC".
std::string utc_now();

// A scene's label in tables: "default" for the built-in scene, else the file's stem.
std::string scene_label(const std::string& scene);

// Wall ms of each of `count` fresh processes `voxr render RENDER_ARGS -q -o TEMP.png [--device DEVICE]`
// (this executable, the image written to a temporary file named by `tag`, removed after). Throws voxr::Error
// when a process fails.
std::vector<double> time_fresh_renders(const std::vector<std::string>& render_args, int count,
                                       const std::string& device, const std::string& tag);

// "| label | triangles | median | min | max |" of those wall times, whole ms, with the newline.
std::string fresh_table_row(const std::string& label, uint64_t triangles, const std::vector<double>& wall_ms);

}  // namespace voxr::cli
