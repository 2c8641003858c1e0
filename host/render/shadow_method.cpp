#include "render/shadow_method.h"

#include "core/named_values.h"

namespace voxr {

const ShadowMethodInfo& shadow_method_info(ShadowMethod method) {
  return named_entry(
      kShadowMethods, [](const ShadowMethodInfo& i) { return i.method; }, method);
}

ShadowMethod parse_shadow_method(std::string_view name) {
  return parse_named(
      kShadowMethods, [](const ShadowMethodInfo& i) { return i.method; }, name, "shadow method");
}

}  // namespace voxr
