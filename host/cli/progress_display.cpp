#include "cli/progress_display.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>

namespace voxr::cli {

ProgressDisplay::ProgressDisplay(bool forced, bool quiet) {
  const bool tty = isatty(fileno(stderr));
  if (tty && (forced || !quiet))
    mode_ = Mode::kTerminal;
  else if (forced)
    mode_ = Mode::kLines;
  else
    mode_ = Mode::kOff;
}

void ProgressDisplay::show(const std::string& step) const {
  if (mode_ == Mode::kTerminal) {
    fmt::print(stderr, "\r{:<60}", step);
    std::fflush(stderr);
  } else if (mode_ == Mode::kLines) {
    fmt::print(stderr, "voxr: [{:7.2f} s] {}\n", ms_since(start_) / 1000.0, step);
    std::fflush(stderr);
  }
}

void ProgressDisplay::clear() const {
  if (mode_ == Mode::kTerminal) fmt::print(stderr, "\r{:<60}\r", "");
}

}  // namespace voxr::cli
