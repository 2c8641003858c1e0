// What the benchmark commands (bench voxelize, bench shadows, bench refraction, ...) share besides
// bench/report_fields.h: the command line, and fresh `voxr render` processes timed as a user runs them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace voxr::cli {

// The process's own command line as the user typed it, the program named "voxr" (voxr-render's argv is
// voxr's, exec'd).
std::string command_line();

// Wall ms of each of `count` fresh processes `voxr render RENDER_ARGS -q -o TEMP.png [--device DEVICE]`
// (this executable, the image written to a temporary file named by `tag`, removed after). Throws voxr::Error
// when a process fails.
std::vector<double> time_fresh_renders(const std::vector<std::string>& render_args, int count,
                                       const std::string& device, const std::string& tag);

// "| label | triangles | median | min | max |" of those wall times, whole ms, with the newline.
std::string fresh_table_row(const std::string& label, uint64_t triangles, const std::vector<double>& wall_ms);

}  // namespace voxr::cli
