#include "render/refraction_method.h"

#include "core/named_values.h"

namespace voxr {

namespace {
constexpr auto kMethodKey = [](const RefractionMethodInfo& i) { return i.method; };
constexpr auto kRuleKey = [](const StepRuleInfo& i) { return i.rule; };
constexpr auto kNormalKey = [](const NormalKindInfo& i) { return i.kind; };
}  // namespace

const RefractionMethodInfo& refraction_method_info(RefractionMethod method) {
  return named_entry(kRefractionMethods, kMethodKey, method);
}
const StepRuleInfo& step_rule_info(StepRule rule) {
  return named_entry(kStepRules, kRuleKey, rule);
}
const NormalKindInfo& normal_kind_info(NormalKind kind) {
  return named_entry(kNormalKinds, kNormalKey, kind);
}
RefractionMethod parse_refraction_method(std::string_view name) {
  return parse_named(kRefractionMethods, kMethodKey, name, "refraction method");
}
StepRule parse_step_rule(std::string_view name) {
  return parse_named(kStepRules, kRuleKey, name, "step rule");
}
NormalKind parse_normal_kind(std::string_view name) {
  return parse_named(kNormalKinds, kNormalKey, name, "normal kind");
}

}  // namespace voxr
