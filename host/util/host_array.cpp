#include "util/host_array.h"

#include <sys/mman.h>

#include <cstring>

namespace voxr {

namespace {
// Below this, an aligned allocation zeroed by hand (mmap's page granularity would waste memory).
constexpr size_t kMapThreshold = size_t(1) << 20;
}  // namespace

void* allocate_zero_pages(size_t bytes) {
  if (bytes >= kMapThreshold) {
    // Populated at once: faulting the pages in one by one later (while a kernel sets bits in them from
    // several threads) costs several times more.
    void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_POPULATE, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
    return p;
  }
  void* p = ::operator new(bytes, std::align_val_t(kHostArrayAlignment));
  std::memset(p, 0, bytes);
  return p;
}

void free_zero_pages(void* p, size_t bytes) {
  if (!p) return;
  if (bytes >= kMapThreshold) {
    munmap(p, bytes);
  } else {
    ::operator delete(p, std::align_val_t(kHostArrayAlignment));
  }
}

}  // namespace voxr
