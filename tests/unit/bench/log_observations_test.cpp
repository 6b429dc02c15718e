// A robot log's scans as the gateway would hand them to the mapper (eval/log_observations.hpp).
#include "eval/log_observations.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace slam::bench {
namespace {

robot_log::LaserScan scan(double stamp, Pose odom) {
  robot_log::LaserScan s;
  s.stamp_s = stamp;
  s.odom = odom;
  s.laser_in_robot = Pose{0.5, 0.0, 0.0};
  s.angle_min_rad = -std::numbers::pi / 2;
  s.angle_increment_rad = std::numbers::pi / 2;
  s.max_range_m = 80.0;
  s.ranges = {2.0f, 81.0f, 40.0f};  // right: a return; ahead: none; left: beyond the range limit
  return s;
}

TEST(LogObservations, ScansBecomeSensorPosesHitsAndMissesInTheOdometryFrame) {
  const std::vector<robot_log::LaserScan> scans{scan(10.0, {1, 2, std::numbers::pi / 2}),
                                                scan(9.5, {1, 2, 0})};
  LogObservationOptions options;
  options.max_range_m = 30.0;
  options.free_range_m = 8.0;  // (the gateway default is 5 m)
  const LogObservations out = log_observations(scans, options);
  ASSERT_EQ(out.observations.size(), 2u);
  const auto& o = out.observations[0];
  EXPECT_EQ(o.seq, 1u);
  EXPECT_NEAR(o.x, 1.0, 1e-12);  // the laser 0.5 m ahead of a robot facing +y
  EXPECT_NEAR(o.y, 2.5, 1e-12);
  EXPECT_TRUE(o.has_heading);
  ASSERT_EQ(o.hits.size(), 1u);
  EXPECT_NEAR(o.hits[0].x, 3.0, 1e-9);  // 2 m to the robot's right is +x
  EXPECT_NEAR(o.hits[0].y, 2.5, 1e-9);
  ASSERT_EQ(o.misses.size(), 2u);  // no return, and a return beyond 30 m: free for 8 m
  EXPECT_NEAR(o.misses[0].y, 10.5, 1e-9);
  EXPECT_NEAR(o.misses[1].x, -7.0, 1e-9);
  // Arrival never goes back, while the robot's own stamps are kept as they were.
  EXPECT_EQ(out.observations[1].stamp_ns, out.observations[0].stamp_ns);
  EXPECT_DOUBLE_EQ(out.stamps_s[1], 9.5);
  EXPECT_NEAR(out.sensor_odom[1].x, 1.5, 1e-12);
}

TEST(LogObservations, LegacyRobotsSendCentimetresAndAtMostSixteenHits) {
  robot_log::LaserScan s = scan(1.0, {1.234567, 0, 0.3});
  s.angle_min_rad = -std::numbers::pi / 2;
  s.angle_increment_rad = std::numbers::pi / 179;
  s.ranges.assign(180, 3.0f);
  LogObservationOptions options;
  options.v1 = true;
  const std::vector<robot_log::LaserScan> scans{s};
  const auto out = log_observations(scans, options);
  const auto& o = out.observations[0];
  EXPECT_FALSE(o.has_heading);
  EXPECT_EQ(o.theta, 0.0);
  EXPECT_EQ(o.hits.size(), 16u);
  EXPECT_TRUE(o.misses.empty());
  EXPECT_NEAR(o.x * 100, std::round(o.x * 100), 1e-9);
  EXPECT_NEAR(o.hits[3].y * 100, std::round(o.hits[3].y * 100), 1e-9);
}

TEST(LogObservations, ThinningKeepsEvenlySpacedBeams) {
  EXPECT_EQ(thinned_beams(180, 4), (std::vector<size_t>{22, 67, 112, 157}));
  EXPECT_EQ(thinned_beams(3, 0).size(), 3u);
  EXPECT_EQ(thinned_beams(3, 10).size(), 3u);
}

}  // namespace
}  // namespace slam::bench
