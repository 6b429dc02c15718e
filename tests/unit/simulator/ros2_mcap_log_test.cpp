// ROS 2 recordings read into scans: a chunked file written by @mcap/core and Foxglove's CDR
// serialiser (tests/node/ros2_scan_mcap_writer.mjs, its scenario restated here), and files made
// with the project's own MCAP writer for topic choice and upside-down lasers.
#include "simulator/robot_log/ros2_mcap_log.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "cdr_bytes.hpp"
#include "common/core/mcap_writer.hpp"
#include "simulator/robot_log/ros2_messages.hpp"
#include "temp_dir.hpp"

namespace slam::robot_log {
namespace {

using ::testing::HasSubstr;

TEST(Ros2McapLog, ReadsARecordingMadeByMcapCore) {
  const std::string node_dir = SLAM_NODE_TESTS_DIR;
  if (std::system("node --version > /dev/null 2>&1") != 0 ||
      !std::filesystem::exists(node_dir + "/node_modules/@mcap/core"))
    GTEST_SKIP() << "node or the pinned npm packages are missing (scripts/setup.sh installs them)";
  const testkit::TempDir dir("ros2-mcap");
  const auto file = dir / "scan.mcap";
  const std::string command = "node " + node_dir + "/ros2_scan_mcap_writer.mjs " + file.string();
  ASSERT_EQ(std::system(command.c_str()), 0) << command;

  auto log = read_ros2_mcap_log(file);
  ASSERT_TRUE(log) << log.message();
  const LogStats& s = log->stats;
  EXPECT_EQ(s.lines, 130);  // 1 tf_static + 101 odometry + 27 on /scan + 1 chatter
  EXPECT_EQ(s.scans, 25);
  EXPECT_EQ(s.odometry, 101);
  EXPECT_EQ(s.unknown_kinds, 1);
  EXPECT_EQ(s.bad_lines, 2);  // the scan at 110 s, the two bytes
  EXPECT_EQ(s.stamps_back, 1);
  EXPECT_THAT(s.first_bad, HasSubstr("message 128: scan at 110.000 s has no odometry"));
  ASSERT_EQ(log->scans.size(), 25u);
  for (size_t j = 0; j < 25; ++j) {
    const LaserScan& scan = log->scans[j];
    const double t = j < 24 ? 100.01 + 0.2 * static_cast<double>(j) : 101.0;
    SCOPED_TRACE(j);
    EXPECT_NEAR(scan.stamp_s, t, 1e-6);
    EXPECT_NEAR(scan.odom.x, 0.5 * (t - 100), 1e-6);
    EXPECT_NEAR(scan.odom.y, 0.0, 1e-9);
    EXPECT_NEAR(scan.odom.theta, 0.2 * (t - 100), 1e-6);
    EXPECT_NEAR(scan.laser_in_robot.x, 0.3, 1e-9);
    EXPECT_NEAR(scan.laser_in_robot.y, 0.1, 1e-9);
    EXPECT_NEAR(scan.laser_in_robot.theta, 0.5, 1e-9);
    EXPECT_FLOAT_EQ(static_cast<float>(scan.angle_min_rad), -1.0f);
    EXPECT_FLOAT_EQ(static_cast<float>(scan.angle_increment_rad), 0.5f);
    EXPECT_FLOAT_EQ(static_cast<float>(scan.max_range_m), 4.0f);
    ASSERT_EQ(scan.ranges.size(), 5u);
    EXPECT_TRUE(scan.is_return(0) && scan.is_return(1) && scan.is_return(4));
    EXPECT_FALSE(scan.is_return(2));  // inf
    EXPECT_FALSE(scan.is_return(3));  // below range_min
  }
}

std::vector<uint8_t> scan_cdr(double t, const std::string& frame) {
  CdrBytes c;
  c.header(static_cast<int32_t>(t), 0, frame).f32(-1).f32(1).f32(1).f32(0).f32(0).f32(0).f32(5);
  c.u32(3).f32(1).f32(2).f32(3).u32(0);
  return c.bytes();
}

std::vector<uint8_t> odom_cdr(double t) {
  CdrBytes c;
  c.header(static_cast<int32_t>(t), 0, "odom").string("base_link").f64(t).f64(0).f64(0);
  c.f64(0).f64(0).f64(0).f64(1);
  return c.bytes();
}

// A recording with the given LaserScan topics (each with a scan at 1 s, frame "laser"), odometry at
// 0, 1 and 2 s unless `with_odometry` is false, and, when `tf` is given, that /tf_static message.
std::filesystem::path recording(const testkit::TempDir& dir, const std::vector<std::string>& scan_topics,
                                bool with_odometry = true, const std::vector<uint8_t>& tf = {}) {
  const auto path = dir / "made.mcap";
  auto writer = mcap::Writer::create(path.string(), "ros2_mcap_log_test");
  EXPECT_TRUE(writer);
  auto& w = **writer;
  const uint16_t scan_schema = *w.add_schema(kLaserScanType, "ros2msg", "");
  const uint16_t odom_schema = *w.add_schema(kOdometryType, "ros2msg", "");
  const uint16_t tf_schema = *w.add_schema(kTfMessageType, "ros2msg", "");
  const uint16_t odom = *w.add_channel(odom_schema, "/odom", "cdr");
  if (!tf.empty()) {
    EXPECT_TRUE(w.write_message(*w.add_channel(tf_schema, "/tf_static", "cdr"), 0, 0, tf));
  }
  for (int t = 0; t < 3 && with_odometry; ++t) EXPECT_TRUE(w.write_message(odom, t, t, odom_cdr(t)));
  for (const std::string& topic : scan_topics)
    EXPECT_TRUE(w.write_message(*w.add_channel(scan_schema, topic, "cdr"), 1, 1, scan_cdr(1, "laser")));
  EXPECT_TRUE(w.close());
  return path;
}

TEST(Ros2McapLog, TopicChoice) {
  const testkit::TempDir dir("ros2-mcap");
  const auto two = recording(dir, {"/scan_front", "/scan_rear"});
  EXPECT_THAT(read_ros2_mcap_log(two).message(),
              HasSubstr("several sensor_msgs/msg/LaserScan topics (/scan_front, /scan_rear)"));
  Ros2McapOptions options;
  options.scan_topic = "/scan_rear";
  auto rear = read_ros2_mcap_log(two, options);
  ASSERT_TRUE(rear) << rear.message();
  EXPECT_EQ(rear->scans.size(), 1u);
  EXPECT_EQ(rear->stats.unknown_kinds, 1);  // the front scan
  EXPECT_NEAR(rear->scans[0].odom.x, 1.0, 1e-12);
  options.scan_topic = "/scan_top";
  EXPECT_THAT(read_ros2_mcap_log(two, options).message(),
              HasSubstr("no sensor_msgs/msg/LaserScan topic '/scan_top'"));
  options.scan_topic.clear();
  options.max_odometry_gap_s = 0;
  EXPECT_FALSE(read_ros2_mcap_log(two, options));
  EXPECT_THAT(read_ros2_mcap_log(recording(dir, {})).message(),
              HasSubstr("no sensor_msgs/msg/LaserScan topic"));
  EXPECT_THAT(read_ros2_mcap_log(dir / "missing.mcap").message(), HasSubstr("cannot open"));
}

TEST(Ros2McapLog, ReadingsThatSayNothingAndScansWithoutOdometryAreCounted) {
  const testkit::TempDir dir("ros2-mcap");
  const auto path = dir / "bad.mcap";
  auto writer = mcap::Writer::create(path.string(), "ros2_mcap_log_test");
  ASSERT_TRUE(writer);
  auto& w = **writer;
  const uint16_t scan_schema = *w.add_schema(kLaserScanType, "ros2msg", "");
  const uint16_t odom_schema = *w.add_schema(kOdometryType, "ros2msg", "");
  const uint16_t odom = *w.add_channel(odom_schema, "/odom", "cdr");
  const uint16_t scans = *w.add_channel(scan_schema, "/scan", "cdr");
  for (int t = 0; t < 3; ++t) EXPECT_TRUE(w.write_message(odom, t, t, odom_cdr(t)));
  // range_min 0.1 m, range_max 5 m: NaN, -inf and 0.05 say nothing; 7 and inf are no return.
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const std::vector<float> ranges{1, nan, -inf, 0.05f, 7, inf, 2};
  CdrBytes c;
  c.header(1, 0, "laser").f32(-1).f32(1).f32(0.5).f32(0).f32(0).f32(0.1f).f32(5);
  c.u32(static_cast<uint32_t>(ranges.size()));
  for (float r : ranges) c.f32(r);
  c.u32(0);
  EXPECT_TRUE(w.write_message(scans, 1, 1, c.bytes()));
  EXPECT_TRUE(w.write_message(scans, 60, 60, scan_cdr(60, "laser")));  // a minute after the odometry ends
  EXPECT_TRUE(w.close());

  auto log = read_ros2_mcap_log(path);
  ASSERT_TRUE(log) << log.message();
  const LogStats& s = log->stats;
  EXPECT_EQ(s.scans, 1);
  EXPECT_EQ(s.bad_lines, 1);  // the scan without a pose
  EXPECT_THAT(s.first_bad, HasSubstr("has no odometry within"));
  EXPECT_EQ(s.error_readings, 3);
  EXPECT_EQ(s.far_readings, 2);
  ASSERT_EQ(log->scans.size(), 1u);
  const LaserScan& scan = log->scans[0];
  for (size_t i = 0; i < ranges.size(); ++i) EXPECT_EQ(scan.is_return(i), i == 0 || i == 6) << "beam " << i;
}

TEST(Ros2McapLog, UpsideDownLaserIsMirrored) {
  const testkit::TempDir dir("ros2-mcap");
  CdrBytes tf;
  tf.u32(1).header(0, 0, "base_link").string("laser");
  tf.f64(0.1).f64(0).f64(0.3).f64(1).f64(0).f64(0).f64(0);  // rolled by pi
  auto log = read_ros2_mcap_log(recording(dir, {"/scan"}, true, tf.bytes()));
  ASSERT_TRUE(log) << log.message();
  ASSERT_EQ(log->scans.size(), 1u);
  const LaserScan& scan = log->scans[0];
  EXPECT_NEAR(scan.laser_in_robot.x, 0.1, 1e-12);
  // Beams at -1, 0, 1 rad read 1, 2, 3; seen from above they lie at 1, 0, -1.
  EXPECT_DOUBLE_EQ(scan.angle_min_rad, -1.0);
  EXPECT_EQ(scan.ranges, (std::vector<float>{3, 2, 1}));
}

}  // namespace
}  // namespace slam::robot_log
