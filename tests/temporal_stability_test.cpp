// The temporal family of the stability suite, small version (stability/stability_case.h): every method's
// flicker on the moving and deforming scenes stays within its bound, and no frame has a non-finite pixel.
#include <gtest/gtest.h>

#include <cstdio>

#include "stability/stability_case.h"
#include "test_support.h"

namespace voxr {
namespace {

TEST(TemporalStability, EveryRowOfTheSmallVersionPasses) {
  StabilityContext ctx{test::runtime(), false, {}, {}};
  const std::vector<StabilityCase> cases = temporal_stability_cases();
  ASSERT_EQ(cases.size(), 2u);
  size_t rows = 0;
  for (const StabilityCase& c : cases) {
    EXPECT_EQ(c.family, "temporal");
    for (const StabilityRow& r : c.run(ctx)) {
      ++rows;
      std::printf("[  NOTE    ] %s %s: %s = %.5f (bound %.5f)\n", r.name.c_str(), r.method.c_str(),
                  r.measure.c_str(), r.value, r.bound);
      EXPECT_TRUE(r.pass()) << r.name << " " << r.method << ": " << r.measure << " = " << r.value
                            << " > bound " << r.bound << " (" << r.note << ")";
    }
  }
  EXPECT_EQ(rows, 2u * (5 + 4));  // flicker and non-finite pixels per method: 5 shadow, 4 refraction
}

}  // namespace
}  // namespace voxr
