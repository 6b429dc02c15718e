// CARMEN log lines: each kind the reader knows, the angle convention of lasers without angles, the
// laser mount from PARAM lines and from ROBOTLASER1 poses, and junk refused with a reason.
#include "simulator/robot_log/carmen_line.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace slam::robot_log {
namespace {

using ::testing::HasSubstr;
constexpr double kPi = std::numbers::pi;

// A FLASER line with n readings of 1.5 m.
std::string flaser(int n, std::string_view kind = "FLASER") {
  std::string line = std::string(kind) + " " + std::to_string(n);
  for (int i = 0; i < n; ++i) line += " 1.5";
  return line + " 1.1 2.1 0.6 1.0 2.0 0.5 100.25 host 100.3";
}

TEST(CarmenLine, FlaserScan) {
  CarmenContext context;
  auto r = parse_carmen_line("FLASER 4 1.0 2.5 81.91 0.3 5 6 0.1 1 2 0.5 12.5 myhost 12.6", context);
  ASSERT_TRUE(r) << r.message();
  ASSERT_EQ(r->kind, CarmenKind::Scan);
  const LaserScan& s = *r->scan;
  EXPECT_DOUBLE_EQ(s.stamp_s, 12.5);
  EXPECT_EQ(s.odom, (Pose{1, 2, 0.5}));
  EXPECT_EQ(s.laser_in_robot, Pose{});
  EXPECT_DOUBLE_EQ(s.angle_min_rad, -kPi / 2);
  EXPECT_DOUBLE_EQ(s.angle_increment_rad, kPi / 4);
  EXPECT_DOUBLE_EQ(s.max_range_m, 81.0);
  ASSERT_EQ(s.ranges.size(), 4u);
  EXPECT_FLOAT_EQ(s.ranges[1], 2.5f);
  EXPECT_TRUE(s.is_return(0));
  EXPECT_FALSE(s.is_return(2));  // 81.91: the benchmark lasers' "nothing"
}

TEST(CarmenLine, FlaserAnglesFollowTheBeamCount) {
  CarmenContext context;
  const auto increment = [&](int n) {
    return parse_carmen_line(flaser(n), context)->scan->angle_increment_rad;
  };
  EXPECT_NEAR(increment(180), kPi / 180, 1e-12);  // -90 .. +89 degrees
  EXPECT_NEAR(increment(181), kPi / 180, 1e-12);  // -90 .. +90
  EXPECT_NEAR(increment(360), kPi / 360, 1e-12);
  EXPECT_NEAR(increment(361), kPi / 360, 1e-12);
  EXPECT_EQ(increment(1), 0.0);
  auto empty = parse_carmen_line(flaser(0), context);
  ASSERT_TRUE(empty) << empty.message();
  EXPECT_TRUE(empty->scan->ranges.empty());
}

TEST(CarmenLine, MaxRangeIsAnOption) {
  CarmenContext context;
  CarmenOptions options;
  options.flaser_max_range_m = 1.2;
  EXPECT_DOUBLE_EQ(parse_carmen_line(flaser(3), context, options)->scan->max_range_m, 1.2);
  options.flaser_max_range_m = 0;
  EXPECT_FALSE(options.validate());
  EXPECT_TRUE(CarmenOptions{}.validate());
}

TEST(CarmenLine, ReadingsThatSayNothingKeepTheScan) {
  // NaN (an error reading), negative and zero readings say nothing; inf and readings at or beyond
  // the maximum are no return. The scan keeps them all as read, and its good beams.
  CarmenContext context;
  auto r = parse_carmen_line("FLASER 8 1.5 nan -nan -1 0 inf 90 -inf 0 0 0 1 2 0.5 7.5 host 7.5", context);
  ASSERT_TRUE(r) << r.message();
  const LaserScan& s = *r->scan;
  ASSERT_EQ(s.ranges.size(), 8u);
  EXPECT_TRUE(s.is_return(0));
  for (size_t i = 1; i < 8; ++i) EXPECT_FALSE(s.is_return(i)) << "beam " << i;
  EXPECT_TRUE(std::isnan(s.ranges[1]) && std::isnan(s.ranges[2]));
  EXPECT_FLOAT_EQ(s.ranges[3], -1.0f);
  EXPECT_GE(s.ranges[5], s.max_range_m);  // inf: no return
  EXPECT_LE(s.ranges[7], 0.0f);           // -inf: an error reading
  EXPECT_EQ(s.odom, (Pose{1, 2, 0.5}));
  auto robot = parse_carmen_line(
      "ROBOTLASER1 0 -1 2 1 50 0.01 0 3 nan 60 2 0 0 0 0 0 0 0 0 0 0 0 0 1.4 host 1.4", context);
  ASSERT_TRUE(robot) << robot.message();
  EXPECT_TRUE(std::isnan(robot->scan->ranges[0]));
  EXPECT_FALSE(robot->scan->is_return(1));  // 60 m: beyond its 50 m
  EXPECT_TRUE(robot->scan->is_return(2));
}

TEST(CarmenLine, ParamOffsetsPlaceTheLasers) {
  CarmenContext context;
  auto param = parse_carmen_line("PARAM robot_frontlaser_offset 0.040000 bag 1211.52", context);
  ASSERT_TRUE(param) << param.message();
  EXPECT_EQ(param->kind, CarmenKind::Param);
  EXPECT_DOUBLE_EQ(context.front_laser_offset_m, 0.04);
  ASSERT_TRUE(parse_carmen_line("PARAM robot_rearlaser_offset -0.2", context));
  ASSERT_TRUE(parse_carmen_line("PARAM robot_max_velocity 0.5 host 1", context));  // ignored

  EXPECT_EQ(parse_carmen_line(flaser(2), context)->scan->laser_in_robot, (Pose{0.04, 0, 0}));
  const auto rear = parse_carmen_line(flaser(2, "RLASER"), context);
  ASSERT_TRUE(rear) << rear.message();
  EXPECT_EQ(rear->scan->laser_in_robot, (Pose{-0.2, 0, kPi}));

  EXPECT_FALSE(parse_carmen_line("PARAM robot_frontlaser_offset ahead", context));
  EXPECT_FALSE(parse_carmen_line("PARAM", context));
  EXPECT_DOUBLE_EQ(context.front_laser_offset_m, 0.04);  // a bad PARAM changes nothing
}

TEST(CarmenLine, RobotLaserCarriesItsOwnGeometry) {
  // 3 readings, 2 remissions; laser 0.2 m ahead of a robot at (1, 1) heading +90 degrees.
  const std::string line =
      "ROBOTLASER1 0 -1.5 3.0 1.5 50.0 0.01 0 3 1.0 50.0 2.0 2 0.5 0.6 "
      "1.0 1.2 1.5707963267948966 1.0 1.0 1.5707963267948966 0.1 0.0 0.5 0.3 0 77.5 host 77.6";
  CarmenContext context;
  auto r = parse_carmen_line(line, context);
  ASSERT_TRUE(r) << r.message();
  const LaserScan& s = *r->scan;
  EXPECT_DOUBLE_EQ(s.stamp_s, 77.5);
  EXPECT_NEAR(s.odom.x, 1.0, 1e-12);
  EXPECT_NEAR(s.odom.theta, kPi / 2, 1e-12);
  EXPECT_NEAR(s.laser_in_robot.x, 0.2, 1e-9);
  EXPECT_NEAR(s.laser_in_robot.y, 0.0, 1e-9);
  EXPECT_NEAR(s.laser_in_robot.theta, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(s.angle_min_rad, -1.5);
  EXPECT_DOUBLE_EQ(s.angle_increment_rad, 1.5);
  EXPECT_DOUBLE_EQ(s.max_range_m, 50.0);
  ASSERT_EQ(s.ranges.size(), 3u);
  EXPECT_FALSE(s.is_return(1));
  EXPECT_TRUE(s.is_return(2));
}

TEST(CarmenLine, OtherKinds) {
  CarmenContext context;
  EXPECT_EQ(parse_carmen_line("ODOM 1 2 0.5 0.1 0 0 12.5 host 12.5", context)->kind, CarmenKind::Odometry);
  EXPECT_EQ(parse_carmen_line("# a comment", context)->kind, CarmenKind::Comment);
  EXPECT_EQ(parse_carmen_line("   \r", context)->kind, CarmenKind::Comment);
  EXPECT_EQ(parse_carmen_line("TRUEPOS 1 2 3 4 5 6 7 h 8", context)->kind, CarmenKind::Unknown);
  auto tabs = parse_carmen_line("ODOM\t1 2 0.5 0.1 0 0 12.5 host 12.5\r", context);
  ASSERT_TRUE(tabs) << tabs.message();
}

TEST(CarmenLine, JunkIsAnError) {
  CarmenContext context;
  const auto reason = [&](std::string_view line) {
    auto r = parse_carmen_line(line, context);
    return r ? std::string("parsed") : r.message();
  };
  EXPECT_THAT(reason("FLASER 3 1 2 0 0 0 0 0 0 1 h 1"), HasSubstr("expected 14"));    // one reading short
  EXPECT_THAT(reason("FLASER 2 1 2 0 0 0 0 0 0 1 h 1 9"), HasSubstr("expected 13"));  // one field too many
  EXPECT_THAT(reason("FLASER 2 1 x 0 0 0 0 0 0 1 h 1"), HasSubstr("reading 1 is not a number"));
  EXPECT_THAT(reason("FLASER 2 1 2 0 0 inf 0 0 0 1 h 1"), HasSubstr("not a finite number"));
  // A scan without a usable pose or stamp.
  EXPECT_THAT(reason("FLASER 2 1 2 0 0 0 nan 0 0 1 h 1"), HasSubstr("not a finite number"));
  EXPECT_THAT(reason("FLASER 2 1 2 0 0 0 0 0 0 nan h 1"), HasSubstr("not a finite number"));
  EXPECT_THAT(reason("FLASER 2 1 2 0 0 0 1 h 1"), HasSubstr("expected 13"));  // no odometry pose
  EXPECT_THAT(reason("FLASER 2 1 2 0 0 0 0 0 0 x h 1"), HasSubstr("not a finite number"));
  EXPECT_THAT(reason("FLASER -2 1 2"), HasSubstr("reading count"));
  EXPECT_THAT(reason("FLASER 99999999999999999999"), HasSubstr("reading count"));
  EXPECT_THAT(reason("FLASER 1000000 1"), HasSubstr("expected"));
  EXPECT_THAT(reason("FLASER"), HasSubstr("reading count"));
  EXPECT_THAT(reason("ODOM 1 2 3"), HasSubstr("expected 10"));
  EXPECT_THAT(reason("ROBOTLASER1 0 0 3 1 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 1 h 1"),
              HasSubstr("maximum_range"));
  EXPECT_THAT(reason("ROBOTLASER1 0 0 3 1 50 0 0 5 1"), HasSubstr("remission count"));
  EXPECT_THAT(reason("fl\xffser 1 2"), HasSubstr("not a record kind"));
}

}  // namespace
}  // namespace slam::robot_log
