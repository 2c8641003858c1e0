#include "cli/frame_pattern.h"

#include <fmt/format.h>

#include <cctype>

#include "util/error.h"

namespace voxr::cli {

std::string FramePattern::name(uint32_t frame) const {
  return fmt::format("{}{:0{}d}{}", prefix, frame, width, suffix);
}

std::optional<FramePattern> parse_frame_pattern(const std::string& output, const std::string& option) {
  const size_t percent = output.find('%');
  if (percent == std::string::npos) return std::nullopt;
  const auto bad = [&](const char* why) -> void {
    fail("{} {}: {}; a frame field is %d or %0Nd (e.g. out_%04d.png), exactly one", option, output, why);
  };
  FramePattern p;
  p.prefix = output.substr(0, percent);
  size_t i = percent + 1;
  if (i < output.size() && output[i] == '0') {
    size_t digits = 0;
    ++i;
    while (i < output.size() && std::isdigit(static_cast<unsigned char>(output[i])) && digits < 3)
      p.width = p.width * 10 + (output[i++] - '0'), ++digits;
    if (digits == 0 || digits > 2 || p.width == 0) bad("the width after %0 must be 1 to 99");
  }
  if (i >= output.size() || output[i] != 'd') bad("'%' starts no %d or %0Nd field");
  p.suffix = output.substr(i + 1);
  if (p.suffix.find('%') != std::string::npos) bad("more than one '%'");
  return p;
}

}  // namespace voxr::cli
