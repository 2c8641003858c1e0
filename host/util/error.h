// Two tiers of errors. User mistakes (bad file, bad flag, bad scene) throw voxr::Error with a message that
// names the file and the field at fault; only main() turns them into an exit code. Programmer mistakes hit
// VOXR_CHECK* which print the failed expression and both values, then throw voxr::InternalError.
#pragma once

#include <fmt/format.h>

#include <string>

#include "voxr/error.h"  // Error, InternalError: one definition for the internals and the public API

namespace voxr {

template <typename... Args>
[[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) {
  throw Error(fmt::format(format, std::forward<Args>(args)...));
}

}  // namespace voxr

#define VOXR_CHECK(cond)                                                                              \
  do {                                                                                                \
    if (!(cond))                                                                                      \
      throw ::voxr::InternalError(fmt::format("{}:{}: CHECK({}) failed", __FILE__, __LINE__, #cond)); \
  } while (0)

#define VOXR_CHECK_OP(a, op, b)                                                                              \
  do {                                                                                                       \
    const auto& voxr_a_ = (a);                                                                               \
    const auto& voxr_b_ = (b);                                                                               \
    if (!(voxr_a_ op voxr_b_))                                                                               \
      throw ::voxr::InternalError(fmt::format("{}:{}: CHECK({} {} {}) failed: {} vs {}", __FILE__, __LINE__, \
                                              #a, #op, #b, voxr_a_, voxr_b_));                               \
  } while (0)

#define VOXR_CHECK_EQ(a, b) VOXR_CHECK_OP(a, ==, b)
#define VOXR_CHECK_NE(a, b) VOXR_CHECK_OP(a, !=, b)
#define VOXR_CHECK_LT(a, b) VOXR_CHECK_OP(a, <, b)
#define VOXR_CHECK_LE(a, b) VOXR_CHECK_OP(a, <=, b)
