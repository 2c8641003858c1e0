// The small version of every voxelization stability case (host/stability/voxelization_stability.cpp): each
// row within its bound, the failing rows printed.
#include <gtest/gtest.h>

#include "stability/stability_suite.h"
#include "test_support.h"

namespace voxr {
namespace {

class VoxelizationStability : public testing::TestWithParam<size_t> {};

TEST_P(VoxelizationStability, EveryRowWithinItsBound) {
  const std::vector<StabilityCase> cases = voxelization_stability_cases();
  StabilityContext ctx{test::runtime(), false, {}, {}};
  const std::vector<StabilityCaseResult> results = run_stability_cases({cases[GetParam()]}, ctx);
  for (const std::string& line : stability_failures(results)) ADD_FAILURE() << line;
  for (const StabilityRow& row : results[0].rows) {
    EXPECT_EQ(row.family, "voxelization");
    EXPECT_EQ(row.name.rfind(cases[GetParam()].name.substr(0, cases[GetParam()].name.find('/')), 0), 0u)
        << row.name;
  }
}

std::string case_name(const testing::TestParamInfo<size_t>& info) {
  std::string name = voxelization_stability_cases()[info.param].name;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Cases, VoxelizationStability,
                         testing::Range(size_t(0), voxelization_stability_cases().size()), case_name);

}  // namespace
}  // namespace voxr
