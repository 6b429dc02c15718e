// PointPacer: steps sized from measured frames so a re-render frame stays near its target time.
#include "viewer/core/point_pacer.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace slam::viewer {
namespace {

PacerConfig config() {
  PacerConfig c;
  c.frame_ms = 60.0;
  c.min_points = 5'000;
  c.max_points = 2'000'000;
  c.first_points = 50'000;
  return c;
}

// Feeds frames of a renderer costing base_ms plus ms_per_point per point until the budget settles.
uint64_t settle(PointPacer& p, double base_ms, double ms_per_point, int frames = 60) {
  p.record(0, base_ms);
  for (int i = 0; i < frames; ++i) {
    const uint64_t n = p.budget();
    p.record(n, base_ms + ms_per_point * static_cast<double>(n));
  }
  return p.budget();
}

TEST(PointPacer, StartsWithTheFirstStepUntilSomethingIsMeasured) {
  PointPacer p(config());
  EXPECT_EQ(p.budget(), 50'000u);
  p.record(0, 12.0);  // a light frame teaches the base only
  EXPECT_EQ(p.budget(), 50'000u);
  EXPECT_DOUBLE_EQ(p.base_ms(), 12.0);
}

TEST(PointPacer, FillsTheRoomBetweenBaseAndTarget) {
  PointPacer p(config());
  // 10 ms base, 0.5 us per point: 50 ms of room holds 100,000 points.
  const uint64_t n = settle(p, 10.0, 0.0005);
  EXPECT_NEAR(static_cast<double>(n), 100'000.0, 1'000.0);
  EXPECT_NEAR(10.0 + 0.0005 * static_cast<double>(n), 60.0, 1.0);
}

TEST(PointPacer, SlowerRendererGetsSmallerSteps) {
  PointPacer fast(config());
  PointPacer slow(config());
  EXPECT_GT(settle(fast, 10.0, 0.0002), 4 * settle(slow, 10.0, 0.001));
}

TEST(PointPacer, GrowsAtMostTwofoldPerMeasuredStep) {
  PointPacer p(config());
  p.record(0, 10.0);
  p.record(50'000, 10.0);  // no measurable cost: the estimate alone would allow max_points
  EXPECT_EQ(p.budget(), 100'000u);
  p.record(100'000, 10.0);
  EXPECT_EQ(p.budget(), 200'000u);
}

TEST(PointPacer, OneStallShrinksTheNextStepButDoesNotCollapseIt) {
  PointPacer p(config());
  const uint64_t steady = settle(p, 10.0, 0.0005);
  p.record(steady, 10.0 + 3.0 * 0.0005 * static_cast<double>(steady));  // another process stalled us 3x
  const uint64_t after = p.budget();
  EXPECT_LT(after, steady * 3 / 4);
  EXPECT_GT(after, steady / 3);
  // Back to normal: the budget recovers within a few frames.
  EXPECT_NEAR(static_cast<double>(settle(p, 10.0, 0.0005, 20)), static_cast<double>(steady),
              static_cast<double>(steady) * 0.05);
}

TEST(PointPacer, StaysWithinMinAndMax) {
  PointPacer slow(config());
  EXPECT_EQ(settle(slow, 10.0, 0.1), 5'000u);  // 0.1 ms a point: even 5,000 overrun, still progress
  PointPacer over(config());
  EXPECT_EQ(settle(over, 80.0, 0.0001), 5'000u);  // the base alone exceeds the target
  PointPacer fast(config());
  EXPECT_EQ(settle(fast, 1.0, 1e-9), 2'000'000u);
}

TEST(PointPacer, IgnoresNonsenseTimes) {
  PointPacer p(config());
  p.record(100'000, -1.0);
  p.record(100'000, std::numeric_limits<double>::infinity());
  p.record(100'000, std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(p.budget(), 50'000u);
  EXPECT_EQ(p.ms_per_point(), 0.0);
}

TEST(PointPacer, ValidateNamesTheBadSetting) {
  EXPECT_TRUE(validate(config()));
  PacerConfig c = config();
  c.frame_ms = 0.0;
  EXPECT_NE(validate(c).message().find("frame time"), std::string::npos);
  c = config();
  c.max_points = 1'000;
  EXPECT_NE(validate(c).message().find("maximum"), std::string::npos);
  c = config();
  c.first_points = 3'000'000;
  EXPECT_NE(validate(c).message().find("first step"), std::string::npos);
  c = config();
  c.min_points = 0;
  EXPECT_NE(validate(c).message().find("minimum"), std::string::npos);
}

}  // namespace
}  // namespace slam::viewer
