// The four solid (interior) voxelization modes; see host/voxelize/solid_fill.h for their exact rules.
#pragma once

#include <string_view>

namespace voxr {

enum class SolidMode {
  kXor,     // the papers' XOR of surface voxels along z (slab granularity, Fang & Chen)
  kLate,    // the papers' late filling: parity per column, odd ("questionable") columns repaired from
            // neighbours
  kParity,  // exact centre-crossing parity
  kFlood,   // flood fill of the outside over the conservative surface
};

// "xor" | "late" | "parity" | "flood"; throws voxr::Error naming the bad value.
SolidMode parse_solid_mode(std::string_view name);
const char* solid_mode_name(SolidMode mode);

}  // namespace voxr
