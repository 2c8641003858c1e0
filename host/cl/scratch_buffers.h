// Device buffers kept between runs and grown when too small, so repeated work on one runtime — frames,
// benchmark repeats — does not pay for allocation and first-touch page faults every time.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "cl/cl_runtime.h"

namespace voxr {

// One buffer that is reallocated only when a larger size is asked for. Its contents are whatever the last
// user left.
struct GrowingBuffer {
  cl::Buffer buffer;
  uint64_t bytes = 0;  // allocated size

  // The buffer, at least `bytes` (and at least 4) long. Throws voxr::Error naming `what` when the device
  // cannot hold it.
  cl::Buffer& ensure(ClRuntime& cl, uint64_t bytes, const std::string& what);
  void release() { *this = GrowingBuffer{}; }
};

// Growing buffers by name.
class ScratchBuffers {
 public:
  explicit ScratchBuffers(ClRuntime& cl) : cl_(cl) {}

  // The buffer named `what`, at least `bytes` long (see GrowingBuffer::ensure).
  cl::Buffer get(const std::string& what, uint64_t bytes) { return slots_[what].ensure(cl_, bytes, what); }

 private:
  ClRuntime& cl_;
  std::map<std::string, GrowingBuffer> slots_;
};

}  // namespace voxr
