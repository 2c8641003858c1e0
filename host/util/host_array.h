// Host arrays that a CPU OpenCL device can use in place, with no copy: CL_MEM_USE_HOST_PTR buffers are
// zero-copy only on memory aligned to the device's base-address alignment (128 bytes on PoCL, 4096 on some
// CPU runtimes), so these arrays are page-aligned. Uploading a million-triangle mesh through a copy costs
// tens of milliseconds of page faults on a CPU device; in place it costs nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <new>
#include <utility>
#include <vector>

namespace voxr {

inline constexpr size_t kHostArrayAlignment = 4096;

// Blocks of at least `bytes`, page-aligned and zero: big ones straight from the kernel (mmap, the pages
// populated in one go, cheaper than faulting them in one by one later), small ones zeroed by hand.
void* allocate_zero_pages(size_t bytes);
void free_zero_pages(void* p, size_t bytes);

// The allocator of HostArray (kZeroInit false: page-aligned new, nothing touched, so a large reserve() costs
// nothing until used) and BitWords (kZeroInit true: allocate_zero_pages, and elements constructed without
// arguments are left as the zero memory is, so `BitWords words(n)` needs no clearing pass).
template <typename T, bool kZeroInit>
struct PageAllocator {
  using value_type = T;
  template <typename U>
  struct rebind {
    using other = PageAllocator<U, kZeroInit>;
  };
  PageAllocator() = default;
  template <typename U>
  PageAllocator(const PageAllocator<U, kZeroInit>&) {}
  T* allocate(size_t n) {
    if constexpr (kZeroInit) return static_cast<T*>(allocate_zero_pages(n * sizeof(T)));
    return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t(kHostArrayAlignment)));
  }
  void deallocate(T* p, size_t n) {
    if constexpr (kZeroInit) {
      free_zero_pages(p, n * sizeof(T));
    } else {
      (void)n;
      ::operator delete(p, std::align_val_t(kHostArrayAlignment));
    }
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    if constexpr (kZeroInit && sizeof...(Args) == 0) {
      (void)p;  // zero already
    } else {
      ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
  }
  template <typename U>
  bool operator==(const PageAllocator<U, kZeroInit>&) const {
    return true;
  }
};

// A std::vector whose storage is page-aligned.
template <typename T>
using HostArray = std::vector<T, PageAllocator<T, false>>;

// Dense bit arrays (occupancy, inside): bit (i % 32) of word (i / 32), zero until set. Size them with the
// constructor, assign(), or resize() of an array that never held more elements: elements are not cleared,
// so growing back within a capacity that held bits before (after clear() or a smaller resize) keeps them.
using BitWords = std::vector<uint32_t, PageAllocator<uint32_t, true>>;

}  // namespace voxr
