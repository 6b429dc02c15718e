// RobotFootprints: hits on robots that were just reported nearby become misses; the robot's own
// pose, stale poses and hits elsewhere are left alone.
#include "mapper/core/robot_footprints.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace slam::mapper {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

TEST(RobotFootprints, AHitOnAnotherRobotBecomesAMiss) {
  RobotFootprints f({0.35, 2.0});
  std::vector<Vec2> hits, misses;
  EXPECT_EQ(f.apply("b", {2.0, 0.0}, 0, hits, misses), 0u);  // b reports where it is

  hits = {{1.85, 0.0}, {0.0, 3.0}, {2.1, 0.2}};  // b's near side, a wall, b's flank
  misses = {{-3.0, 0.0}};
  EXPECT_EQ(f.apply("a", {0.0, 0.0}, kSecond / 2, hits, misses), 2u);
  EXPECT_EQ(hits, (std::vector<Vec2>{{0.0, 3.0}}));
  EXPECT_EQ(misses, (std::vector<Vec2>{{-3.0, 0.0}, {1.85, 0.0}, {2.1, 0.2}}));
  EXPECT_EQ(f.robots(), 2u);
}

TEST(RobotFootprints, OwnPoseStalePosesAndAZeroRadiusFilterNothing) {
  RobotFootprints f({0.35, 2.0});
  std::vector<Vec2> hits, misses;
  f.apply("b", {2.0, 0.0}, 0, hits, misses);
  // b's hits near its own position are real (a wall it stands against).
  hits = {{2.1, 0.0}};
  EXPECT_EQ(f.apply("b", {2.0, 0.0}, kSecond, hits, misses), 0u);
  EXPECT_EQ(hits.size(), 1u);
  // Three seconds after b's last report, its old position says nothing about where it is.
  hits = {{1.85, 0.0}};
  EXPECT_EQ(f.apply("a", {0.0, 0.0}, 4 * kSecond, hits, misses), 0u);
  EXPECT_EQ(hits.size(), 1u);

  RobotFootprints off({0.0, 2.0});
  off.apply("b", {2.0, 0.0}, 0, hits, misses);
  hits = {{1.85, 0.0}};
  EXPECT_EQ(off.apply("a", {0.0, 0.0}, 0, hits, misses), 0u);
}

TEST(RobotFootprints, FollowsEachRobotsLatestPose) {
  RobotFootprints f({0.35, 2.0});
  std::vector<Vec2> hits, misses;
  f.apply("b", {2.0, 0.0}, 0, hits, misses);
  f.apply("b", {5.0, 0.0}, kSecond / 10, hits, misses);  // b drove on
  hits = {{1.85, 0.0}, {4.8, 0.0}};
  EXPECT_EQ(f.apply("a", {0.0, 0.0}, kSecond / 5, hits, misses), 1u);
  EXPECT_EQ(hits, (std::vector<Vec2>{{1.85, 0.0}}));  // where b was is a wall now, if seen
}

TEST(RobotFootprints, ConfigIsValidated) {
  EXPECT_TRUE(validate(FootprintConfig{}));
  EXPECT_FALSE(validate(FootprintConfig{-0.1, 2.0}));
  EXPECT_FALSE(validate(FootprintConfig{0.3, 0.0}));
}

}  // namespace
}  // namespace slam::mapper
