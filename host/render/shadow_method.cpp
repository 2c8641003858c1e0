#include "render/shadow_method.h"

namespace voxr {

const ShadowMethodInfo& shadow_method_info(ShadowMethod method) {
  return named_entry(kShadowMethods, method);
}

ShadowMethod parse_shadow_method(std::string_view name) {
  return parse_named(kShadowMethods, name, "shadow method");
}

}  // namespace voxr
