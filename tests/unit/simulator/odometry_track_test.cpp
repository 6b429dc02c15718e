// Odometry at a scan's stamp: interpolated between samples (heading the short way round), held just
// outside the track, refused across gaps, with samples added out of order sorted first.
#include "simulator/robot_log/odometry_track.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace slam::robot_log {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(OdometryTrack, InterpolatesBetweenSamples) {
  OdometryTrack track(0.5);
  track.add(10.0, {0, 0, 0});
  track.add(10.2, {1, 2, 0.4});
  const auto mid = track.at(10.05);
  ASSERT_TRUE(mid);
  EXPECT_NEAR(mid->x, 0.25, 1e-12);
  EXPECT_NEAR(mid->y, 0.5, 1e-12);
  EXPECT_NEAR(mid->theta, 0.1, 1e-12);
  EXPECT_EQ(*track.at(10.2), (Pose{1, 2, 0.4}));
}

TEST(OdometryTrack, HeadingTakesTheShortWayRound) {
  OdometryTrack track;
  track.add(0.0, {0, 0, kPi - 0.1});
  track.add(0.1, {0, 0, -kPi + 0.1});
  EXPECT_NEAR(std::abs(track.at(0.05)->theta), kPi, 1e-9);
}

TEST(OdometryTrack, EdgesAndGaps) {
  OdometryTrack track(1.5);
  EXPECT_FALSE(track.at(1.0));
  track.add(2.0, {2, 0, 0});
  track.add(1.0, {1, 0, 0});  // out of order
  track.add(5.0, {5, 0, 0});
  ASSERT_TRUE(track.at(1.5));
  EXPECT_NEAR(track.at(1.5)->x, 1.5, 1e-12);
  ASSERT_TRUE(track.at(0.7));
  EXPECT_EQ(track.at(0.7)->x, 1.0);  // before the first sample, within the gap: held
  EXPECT_FALSE(track.at(-0.6));
  ASSERT_TRUE(track.at(6.3));
  EXPECT_EQ(track.at(6.3)->x, 5.0);
  EXPECT_FALSE(track.at(6.6));
  EXPECT_FALSE(track.at(3.0));  // 3 s between samples: unknown
  ASSERT_TRUE(track.at(5.0));   // unless a sample is right there
  EXPECT_EQ(track.at(5.0)->x, 5.0);
  EXPECT_EQ(track.size(), 3u);
}

}  // namespace
}  // namespace slam::robot_log
