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

template <typename T>
struct PageAlignedAllocator {
  using value_type = T;
  PageAlignedAllocator() = default;
  template <typename U>
  PageAlignedAllocator(const PageAlignedAllocator<U>&) {}
  T* allocate(size_t n) {
    return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t(kHostArrayAlignment)));
  }
  void deallocate(T* p, size_t) { ::operator delete(p, std::align_val_t(kHostArrayAlignment)); }
  template <typename U>
  bool operator==(const PageAlignedAllocator<U>&) const {
    return true;
  }
};

// A std::vector whose storage is page-aligned.
template <typename T>
using HostArray = std::vector<T, PageAlignedAllocator<T>>;

}  // namespace voxr

namespace voxr {

// Allocator for large bit arrays that start zero: big blocks come straight from the kernel (mmap with the
// pages populated in one go, which is cheaper than faulting them in one by one), already zero, so
// `BitWords words(n)` needs no clearing pass. Elements are not value-initialised (construct() without
// arguments does nothing): the memory is zero already. Page-aligned like HostArray.
template <typename T>
struct ZeroPageAllocator {
  using value_type = T;
  ZeroPageAllocator() = default;
  template <typename U>
  ZeroPageAllocator(const ZeroPageAllocator<U>&) {}
  T* allocate(size_t n);
  void deallocate(T* p, size_t n);
  template <typename U>
  void construct(U* p) {
    (void)p;  // zero already
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <typename U>
  bool operator==(const ZeroPageAllocator<U>&) const {
    return true;
  }
};

// Blocks from and to the kernel (or small zeroed aligned blocks); see ZeroPageAllocator.
void* allocate_zero_pages(size_t bytes);
void free_zero_pages(void* p, size_t bytes);

template <typename T>
T* ZeroPageAllocator<T>::allocate(size_t n) {
  return static_cast<T*>(allocate_zero_pages(n * sizeof(T)));
}

template <typename T>
void ZeroPageAllocator<T>::deallocate(T* p, size_t n) {
  free_zero_pages(p, n * sizeof(T));
}

// Dense bit arrays (occupancy, inside): bit (i % 32) of word (i / 32), zero until set. Size them from empty
// (constructor, resize of an empty array, or assign): a resize that grows back within the capacity keeps
// the old values beyond the former size, as elements are not cleared.
using BitWords = std::vector<uint32_t, ZeroPageAllocator<uint32_t>>;

}  // namespace voxr
