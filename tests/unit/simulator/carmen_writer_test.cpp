// Simulated scans as CARMEN ROBOTLASER1 lines, read back with the log player's own reader: beams in
// the same directions (a full circle and a partial field of view), ranges to 0.1 mm, no-returns
// still no-returns (also for a maximum a float cannot hold), the odometry pose, the sensor mount and
// the stamp as written.
#include "simulator/core/carmen_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "simulator/core/sensor.hpp"
#include "simulator/robot_log/carmen_log.hpp"

namespace slam::sim {
namespace {

constexpr double kPi = std::numbers::pi;

// A report with the sensor's beam layout, every third beam seeing nothing.
RobotReport report_of(const SensorConfig& sensor) {
  RobotReport r;
  r.robot_id = "sim-1";
  r.time_s = 12.35;
  r.reported_pose = {1.5, -2.25, 0.75};
  r.true_pose = {1.4, -2.2, 0.7};
  beam_angles(sensor, r.angles);
  r.max_range = sensor.max_range;
  for (size_t i = 0; i < r.angles.size(); ++i)
    r.ranges.push_back(i % 3 == 0 ? sensor.max_range : 0.5 + 0.123456 * static_cast<double>(i));
  return r;
}

robot_log::LaserScan read_back(const RobotReport& report) {
  std::string text = carmen_header(report.robot_id, "office");
  append_robotlaser_line(report, text);
  const robot_log::RobotLog log = robot_log::parse_carmen_text(text);
  EXPECT_EQ(log.stats.bad_lines, 0) << log.stats.first_bad << "\n" << text;
  EXPECT_EQ(log.stats.comments, 3);
  EXPECT_EQ(log.scans.size(), 1u) << text;
  return log.scans.empty() ? robot_log::LaserScan{} : log.scans[0];
}

void expect_same_scan(const RobotReport& report, const robot_log::LaserScan& scan) {
  EXPECT_DOUBLE_EQ(scan.stamp_s, report.time_s);
  EXPECT_NEAR(scan.odom.x, report.reported_pose.x, 1e-6);
  EXPECT_NEAR(scan.odom.y, report.reported_pose.y, 1e-6);
  EXPECT_NEAR(scan.odom.theta, report.reported_pose.theta, 1e-9);
  ASSERT_EQ(scan.ranges.size(), report.ranges.size());
  for (size_t i = 0; i < report.ranges.size(); ++i) {
    SCOPED_TRACE(i);
    const double angle = scan.angle_min_rad + scan.angle_increment_rad * static_cast<double>(i);
    EXPECT_NEAR(wrap_angle(angle - report.angles[i]), 0.0, 1e-8);
    EXPECT_EQ(scan.is_return(i), report.ranges[i] < report.max_range);
    if (report.ranges[i] < report.max_range) {
      EXPECT_NEAR(scan.ranges[i], report.ranges[i], 1e-4);
    }
  }
}

TEST(CarmenWriter, AFullCircleOfBeamsReadsBackBeamForBeam) {
  const SensorConfig sensor;  // 16 beams all around
  const RobotReport report = report_of(sensor);
  const robot_log::LaserScan scan = read_back(report);
  expect_same_scan(report, scan);
  EXPECT_DOUBLE_EQ(scan.max_range_m, 4.0);
  EXPECT_NEAR(scan.angle_increment_rad, 2 * kPi / 16, 1e-9);
  // At the robot's centre.
  EXPECT_NEAR(scan.laser_in_robot.x, 0.0, 1e-6);
  EXPECT_NEAR(scan.laser_in_robot.y, 0.0, 1e-6);
  EXPECT_NEAR(scan.laser_in_robot.theta, 0.0, 1e-8);
}

TEST(CarmenWriter, APartialFieldOfViewStartsAtItsEdge) {
  SensorConfig sensor;
  sensor.beams = 5;
  sensor.fov = kPi;
  const RobotReport report = report_of(sensor);
  const robot_log::LaserScan scan = read_back(report);
  expect_same_scan(report, scan);
  EXPECT_NEAR(scan.angle_min_rad, -kPi / 2, 1e-9);
  EXPECT_NEAR(scan.angle_increment_rad, kPi / 4, 1e-9);
}

TEST(CarmenWriter, NoReturnStaysNoReturnAndHitsStayHits) {
  SensorConfig sensor;
  sensor.beams = 4;
  sensor.max_range = 4.1;  // no float holds it exactly
  RobotReport report = report_of(sensor);
  report.ranges = {4.1, 4.09999, 4.1, 0.0};
  const robot_log::LaserScan scan = read_back(report);
  EXPECT_FALSE(scan.is_return(0));
  EXPECT_TRUE(scan.is_return(1));  // just short of the maximum: kept a hit
  EXPECT_NEAR(scan.ranges[1], 4.1, 2e-4);
  EXPECT_FALSE(scan.is_return(2));
  EXPECT_FALSE(scan.is_return(3));  // a beam blocked at once reads 0, as the simulator reports it
}

TEST(CarmenWriter, TheSensorMountIsTheLasersPlaceOnTheRobot) {
  RobotReport report = report_of(SensorConfig{});
  report.sensor = Pose{0.2, -0.05, kPi / 2};
  const robot_log::LaserScan scan = read_back(report);
  EXPECT_NEAR(scan.laser_in_robot.x, 0.2, 1e-6);
  EXPECT_NEAR(scan.laser_in_robot.y, -0.05, 1e-6);
  EXPECT_NEAR(scan.laser_in_robot.theta, kPi / 2, 1e-8);
}

TEST(CarmenWriter, StampsHaveSixDecimals) {
  EXPECT_EQ(stamp_text(0.1 + 0.2), "0.300000");
  EXPECT_EQ(stamp_text(1234.5678916), "1234.567892");
}

}  // namespace
}  // namespace slam::sim
