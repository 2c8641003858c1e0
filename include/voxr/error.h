// voxr's errors, shared by the public API (voxr/voxr.h) and the internals (host/util/error.h).
#pragma once

#include <stdexcept>

// Marks what libvoxr exports; everything else in the shared libraries is hidden.
#if defined(VOXR_BUILDING_API)
#define VOXR_API __attribute__((visibility("default")))
#else
#define VOXR_API
#endif

namespace voxr {

// A user mistake or an input voxr cannot process (a bad file, flag, option or scene); what() is one line
// naming the file or option at fault.
class VOXR_API Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A broken internal invariant (a VOXR_CHECK failed): a bug in voxr, never the caller's input.
class VOXR_API InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

}  // namespace voxr
