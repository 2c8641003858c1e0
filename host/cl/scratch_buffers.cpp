#include "cl/scratch_buffers.h"

#include <algorithm>

namespace voxr {

cl::Buffer& GrowingBuffer::ensure(ClRuntime& cl, uint64_t need, const std::string& what) {
  need = std::max<uint64_t>(need, 4);  // OpenCL has no empty buffers
  if (bytes < need) {
    buffer = cl::Buffer();  // release the old one first
    buffer = cl.buffer(need, what);
    bytes = need;
  }
  return buffer;
}

}  // namespace voxr
