// The resolution search behind --error-target: exact choices on error curves given in closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "core/resolution_search.h"
#include "util/error.h"

namespace voxr {
namespace {

TEST(ResolutionSearch, FindsTheSmallestResolutionOnAOneOverRCurve) {
  // error = 1 / r: the target 1/100 is met first at r = 100.
  int calls = 0;
  const ResolutionChoice c = choose_resolution(0.01, 16, 512, [&](uint32_t r) {
    ++calls;
    return 1.0 / r;
  });
  EXPECT_TRUE(c.met);
  EXPECT_GE(c.resolution, 100u);
  EXPECT_LE(c.resolution, 105u);  // within the 5 % the bisection stops at
  EXPECT_LE(c.error, 0.01);
  EXPECT_EQ(c.trials.size(), size_t(calls));
  EXPECT_LE(calls, 8);
}

TEST(ResolutionSearch, SteeperCurvesAreBisected) {
  // error = (64 / r)^3: met from r = 128 on (target 1/8); the 1/r prediction undershoots, bisection ends it.
  const ResolutionChoice c =
      choose_resolution(0.125, 16, 1024, [](uint32_t r) { return std::pow(64.0 / r, 3.0); });
  EXPECT_TRUE(c.met);
  EXPECT_GE(c.resolution, 128u);
  EXPECT_LE(c.resolution, 128u + 128u / 20u);
}

TEST(ResolutionSearch, MetAtTheLowest) {
  const ResolutionChoice c = choose_resolution(1.0, 32, 512, [](uint32_t) { return 0.5; });
  EXPECT_TRUE(c.met);
  EXPECT_EQ(c.resolution, 32u);
  EXPECT_EQ(c.trials.size(), 1u);
}

TEST(ResolutionSearch, AFloorEndsTheSearchNotMet) {
  // Falls to 0.2 at 64, then stays: the target 0.1 cannot be met; the least error is chosen.
  const ResolutionChoice c =
      choose_resolution(0.1, 16, 512, [](uint32_t r) { return r < 64 ? 0.2 * 64.0 / r : 0.2; });
  EXPECT_FALSE(c.met);
  EXPECT_EQ(c.error, 0.2);
  EXPECT_GE(c.resolution, 64u);
  EXPECT_LT(c.trials.back().resolution, 512u);  // stopped at the floor, never measured at 512
}

TEST(ResolutionSearch, NotMetAtTheHighest) {
  const ResolutionChoice c = choose_resolution(1e-6, 16, 256, [](uint32_t r) { return 1.0 / r; });
  EXPECT_FALSE(c.met);
  EXPECT_EQ(c.resolution, 256u);
  EXPECT_DOUBLE_EQ(c.error, 1.0 / 256);
}

TEST(ResolutionSearch, RejectsBadArguments) {
  const auto one = [](uint32_t) { return 1.0; };
  EXPECT_THROW(choose_resolution(-1.0, 16, 512, one), Error);
  EXPECT_THROW(choose_resolution(NAN, 16, 512, one), Error);
  EXPECT_THROW(choose_resolution(0.1, 600, 512, one), Error);
  EXPECT_THROW(choose_resolution(0.1, 16, 512, [](uint32_t) { return double(NAN); }), Error);
}

}  // namespace
}  // namespace voxr
