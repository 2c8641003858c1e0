// What a long command shows on stderr while it works: on a terminal, one line rewritten in place; with
// --progress and stderr not a terminal (a log, a pipe, a batch job), one line per step with the seconds
// since the command started; nothing with -q (unless --progress) or when stderr is not a terminal.
#pragma once

#include <string>

#include "util/clock.h"

namespace voxr::cli {

class ProgressDisplay {
 public:
  // `forced`: --progress; `quiet`: -q.
  ProgressDisplay(bool forced, bool quiet);

  bool active() const { return mode_ != Mode::kOff; }
  // Shows `step` (e.g. "reading bunny.obj", "voxelizing: slab 2/3").
  void show(const std::string& step) const;
  // Clears the terminal line before the command prints its results (no-op for line output).
  void clear() const;
  // Prefix for a warning printed while a terminal line may be showing ("\r" on a terminal).
  const char* line_start() const { return mode_ == Mode::kTerminal ? "\r" : ""; }

 private:
  enum class Mode { kOff, kTerminal, kLines };
  Mode mode_;
  Clock::time_point start_ = Clock::now();
};

}  // namespace voxr::cli
