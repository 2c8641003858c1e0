// The small version of every input stability case (host/stability/input_stability.cpp): each stage gives a
// result or a clear voxr::Error, each input the outcome it must have; the failing rows printed.
#include <gtest/gtest.h>

#include "stability/stability_suite.h"
#include "test_support.h"

namespace voxr {
namespace {

class InputStability : public testing::TestWithParam<size_t> {};

TEST_P(InputStability, EveryRowWithinItsBound) {
  const std::vector<StabilityCase> cases = input_stability_cases();
  StabilityContext ctx{test::runtime(), false, {}, {}};
  const std::vector<StabilityCaseResult> results = run_stability_cases({cases[GetParam()]}, ctx);
  for (const std::string& line : stability_failures(results)) ADD_FAILURE() << line;
  ASSERT_FALSE(results[0].rows.empty());
  EXPECT_EQ(results[0].rows.back().measure.rfind("outcome as expected", 0), 0u);
}

std::string case_name(const testing::TestParamInfo<size_t>& info) {
  std::string name = input_stability_cases()[info.param].name;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Cases, InputStability, testing::Range(size_t(0), input_stability_cases().size()),
                         case_name);

// The NaN input is rejected by validation with a message naming the file and the problem.
TEST(InputStabilityRows, NanVertexRejectedWithAClearMessage) {
  for (const StabilityCase& c : input_stability_cases()) {
    if (c.name != "input/nan-vertex") continue;
    StabilityContext ctx{test::runtime(), false, {}, {}};
    const std::vector<StabilityRow> rows = c.run(ctx);
    ASSERT_GE(rows.size(), 2u);
    const StabilityRow& rejected = rows[rows.size() - 2];
    EXPECT_NE(rejected.note.find("error: "), std::string::npos) << rejected.note;
    EXPECT_NE(rejected.note.find("nan-vertex.obj"), std::string::npos) << rejected.note;
    return;
  }
  FAIL() << "no input/nan-vertex case";
}

}  // namespace
}  // namespace voxr
