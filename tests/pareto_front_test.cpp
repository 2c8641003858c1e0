// The Pareto front of hand-made points: exact membership, ties, NaN.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "bench/pareto_front.h"

namespace voxr {
namespace {

TEST(ParetoFront, KeepsExactlyTheUnbeatenPoints) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // (time, error): (3, 0.3) is beaten by (2, 0.2); (4, 0.2) by (2, 0.2) (slower, as accurate); (5, nan) never
  // counts; the two (2, 0.2) tie and stay together; (6, 0.05) is the most accurate; (1, 0.5) the fastest.
  const std::vector<ParetoPoint> points = {{1, 0.5}, {2, 0.2}, {3, 0.3},  {2, 0.2},
                                           {4, 0.2}, {5, nan}, {6, 0.05}, {1.5, 0.5}};
  const std::vector<bool> expected = {true, true, false, true, false, false, true, false};
  EXPECT_EQ(pareto_front(points), expected);
}

TEST(ParetoFront, NanBeatsNothingAndEmptyIsEmpty) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(pareto_front({{nan, 0.0}, {1.0, 0.1}}), (std::vector<bool>{false, true}));
  EXPECT_EQ(pareto_front({{1.0, nan}, {2.0, 0.1}}), (std::vector<bool>{false, true}));
  EXPECT_TRUE(pareto_front({}).empty());
  EXPECT_EQ(pareto_front({{3.0, 0.0}}), (std::vector<bool>{true}));
}

}  // namespace
}  // namespace voxr
