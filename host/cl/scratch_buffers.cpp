#include "cl/scratch_buffers.h"

#include <algorithm>

namespace voxr {

cl::Buffer ScratchBuffers::get(const std::string& what, uint64_t bytes) {
  bytes = std::max<uint64_t>(bytes, 4);  // OpenCL has no empty buffers
  Slot& slot = slots_[what];
  if (slot.bytes < bytes) {
    slot.buffer = cl::Buffer();  // release the old one first
    slot.buffer = cl_.buffer(bytes, what);
    slot.bytes = bytes;
  }
  return slot.buffer;
}

}  // namespace voxr
