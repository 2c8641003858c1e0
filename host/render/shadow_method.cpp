#include "render/shadow_method.h"

#include <string>

#include "core/error.h"

namespace voxr {

const ShadowMethodInfo& shadow_method_info(ShadowMethod method) {
  for (const ShadowMethodInfo& info : kShadowMethods)
    if (info.method == method) return info;
  throw InternalError("unknown shadow method");
}

ShadowMethod parse_shadow_method(std::string_view name) {
  std::string known;
  for (const ShadowMethodInfo& info : kShadowMethods) {
    if (name == info.name) return info.method;
    known += (known.empty() ? "" : ", ") + std::string(info.name);
  }
  fail("unknown shadow method '{}' (known: {})", name, known);
}

}  // namespace voxr
