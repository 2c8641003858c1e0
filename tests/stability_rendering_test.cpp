// The stability suite's rendering family, small version (host/stability/rendering_stability.cpp): every
// case runs every shadow or refraction method against the exact references and every row must be within its
// bound. A failing row is printed with its value, bound and note.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <string>
#include <vector>

#include "stability/stability_case.h"
#include "test_support.h"

namespace voxr {
namespace {

const std::vector<StabilityCase>& cases() {
  static const std::vector<StabilityCase> all = rendering_stability_cases();
  return all;
}

std::string row_text(const StabilityRow& r) {
  return fmt::format("{} | {} | {}: {:.6g} {} bound {:.6g} ({})", r.name, r.method, r.measure, r.value,
                     r.at_least ? ">=" : "<=", r.bound, r.note);
}

class RenderingStability : public testing::TestWithParam<size_t> {};

TEST_P(RenderingStability, EveryRowWithinItsBound) {
  const StabilityCase& c = cases().at(GetParam());
  StabilityContext ctx{test::runtime(), false, {}, {}};
  const std::vector<StabilityRow> rows = c.run(ctx);
  ASSERT_FALSE(rows.empty()) << c.name;
  for (const StabilityRow& r : rows) {
    EXPECT_EQ(r.family, "rendering");
    EXPECT_EQ(r.name, c.name);
    EXPECT_TRUE(r.picture.empty()) << "no picture_dir, no pictures";
    EXPECT_TRUE(r.pass()) << row_text(r);
  }
}

TEST(RenderingStabilityCases, NamedAndDescribed) {
  ASSERT_GE(cases().size(), 8u);
  for (const StabilityCase& c : cases()) {
    EXPECT_EQ(c.family, "rendering");
    EXPECT_FALSE(c.name.empty());
    EXPECT_FALSE(c.description.empty()) << c.name;
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, RenderingStability, testing::Range<size_t>(0, cases().size()),
                         [](const testing::TestParamInfo<size_t>& info) {
                           std::string name = cases().at(info.param).name;
                           for (char& ch : name)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return name;
                         });

}  // namespace
}  // namespace voxr
