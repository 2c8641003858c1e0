// A loop over [0, count) split into fixed blocks that std::threads take in turn, one thread per core: the
// reference's per-pixel and per-sample work. Each index is computed by exactly one call, so the output does
// not depend on the number of threads or their timing.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace voxr {

// Calls body(begin, end) for consecutive blocks of at most `block` indices covering [0, count), on up to
// std::thread::hardware_concurrency() threads (fewer if the system refuses more). An exception thrown by a
// body is rethrown here (of several, the one from the lowest block); blocks not yet started are skipped once
// one has thrown.
template <typename Body>
void parallel_blocks(size_t count, size_t block, Body&& body) {
  if (count == 0) return;
  block = std::max<size_t>(block, 1);
  const size_t blocks = (count + block - 1) / block;
  const size_t threads = std::min<size_t>(std::max(1u, std::thread::hardware_concurrency()), blocks);
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex error_mutex;
  std::exception_ptr error;
  size_t error_block = blocks;
  auto work = [&] {
    for (;;) {
      const size_t b = next.fetch_add(1);
      if (b >= blocks || failed.load()) return;
      try {
        body(b * block, std::min(count, (b + 1) * block));
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (b < error_block) {
          error_block = b;
          error = std::current_exception();
        }
        failed = true;
      }
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(threads - 1);
  for (size_t t = 1; t < threads; ++t) {
    try {
      pool.emplace_back(work);
    } catch (const std::system_error&) {
      break;  // no more threads: the ones running (and this one) take every block
    }
  }
  work();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace voxr
