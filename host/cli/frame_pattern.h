// Output names with a printf-style frame field for `voxr render --frames N`: "out_%04d.png" names frame 7
// "out_0007.png". Only %d and %0Nd (N one or two digits) are fields; a name holds at most one.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace voxr::cli {

struct FramePattern {
  std::string prefix, suffix;
  int width = 0;  // %0Nd: N, zero-padded; %d: 0

  // The name of frame `frame` (0-based).
  std::string name(uint32_t frame) const;
};

// The frame field of `output`, or nothing when it has no '%'. Throws voxr::Error naming `option` and the
// name for a second field or any other '%' (%s, %5d, %%, a '%' at the end, ...).
std::optional<FramePattern> parse_frame_pattern(const std::string& output, const std::string& option);

}  // namespace voxr::cli
