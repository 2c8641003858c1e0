#include "voxelize/solid_mode.h"

#include "util/error.h"

namespace voxr {

SolidMode parse_solid_mode(std::string_view name) {
  if (name == "xor") return SolidMode::kXor;
  if (name == "late") return SolidMode::kLate;
  if (name == "parity") return SolidMode::kParity;
  if (name == "flood") return SolidMode::kFlood;
  fail("unknown solid mode '{}' (modes: xor, late, parity, flood)", name);
}

const char* solid_mode_name(SolidMode mode) {
  switch (mode) {
    case SolidMode::kXor:
      return "xor";
    case SolidMode::kLate:
      return "late";
    case SolidMode::kParity:
      return "parity";
    case SolidMode::kFlood:
      return "flood";
  }
  return "?";
}

}  // namespace voxr
