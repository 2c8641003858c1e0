#include "render/refraction_method.h"

namespace voxr {

const RefractionMethodInfo& refraction_method_info(RefractionMethod method) {
  return named_entry(kRefractionMethods, method);
}
const StepRuleInfo& step_rule_info(StepRule rule) {
  return named_entry(kStepRules, rule);
}
const NormalKindInfo& normal_kind_info(NormalKind kind) {
  return named_entry(kNormalKinds, kind);
}
const RefractionGridInfo& refraction_grid_info(RefractionGrid grid) {
  return named_entry(kRefractionGrids, grid);
}
RefractionMethod parse_refraction_method(std::string_view name) {
  return parse_named(kRefractionMethods, name, "refraction method");
}
StepRule parse_step_rule(std::string_view name) {
  return parse_named(kStepRules, name, "step rule");
}
NormalKind parse_normal_kind(std::string_view name) {
  return parse_named(kNormalKinds, name, "normal kind");
}
RefractionGrid parse_refraction_grid(std::string_view name) {
  return parse_named(kRefractionGrids, name, "refraction grid");
}

}  // namespace voxr
