// Device scratch buffers kept between runs and grown when too small, so repeated work on one runtime —
// frames, benchmark repeats — does not pay for allocation and first-touch page faults every time.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "cl/cl_runtime.h"

namespace voxr {

class ScratchBuffers {
 public:
  explicit ScratchBuffers(ClRuntime& cl) : cl_(cl) {}

  // The buffer named `what`, at least `bytes` (and at least 4) long; its contents are whatever the last
  // user left. `what` also names it in out-of-memory errors.
  cl::Buffer get(const std::string& what, uint64_t bytes);

 private:
  struct Slot {
    cl::Buffer buffer;
    uint64_t bytes = 0;
  };
  ClRuntime& cl_;
  std::map<std::string, Slot> slots_;
};

}  // namespace voxr
