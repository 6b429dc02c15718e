// ROS 2 messages from CDR bytes built here field by field: classic CDR in both byte orders and
// plain CDR2 (8-byte values aligned to 4), and truncated or unknown encodings refused.
#include "simulator/robot_log/ros2_messages.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cdr_bytes.hpp"

namespace slam::robot_log {
namespace {

using ::testing::HasSubstr;

std::vector<uint8_t> laser_scan(bool little_endian) {
  CdrBytes c(little_endian);
  c.header(12, 500000000, "laser").f32(-1).f32(1).f32(0.5f).f32(0).f32(0.1f).f32(0.05f).f32(4);
  c.u32(3).f32(1).f32(2.5f).f32(9);
  c.u32(0);  // intensities
  return c.bytes();
}

TEST(Ros2Messages, LaserScanInEitherByteOrder) {
  for (bool little : {true, false}) {
    auto scan = decode_laser_scan(laser_scan(little));
    ASSERT_TRUE(scan) << scan.message();
    EXPECT_DOUBLE_EQ(scan->header.stamp_s, 12.5);
    EXPECT_EQ(scan->header.frame_id, "laser");
    EXPECT_FLOAT_EQ(scan->angle_min, -1);
    EXPECT_FLOAT_EQ(scan->angle_increment, 0.5f);
    EXPECT_FLOAT_EQ(scan->range_min, 0.05f);
    EXPECT_FLOAT_EQ(scan->range_max, 4);
    EXPECT_EQ(scan->ranges, (std::vector<float>{1, 2.5f, 9}));
  }
}

// Odometry up to its orientation; the string before the 8-byte fields makes the alignment differ.
std::vector<uint8_t> odometry(bool cdr2) {
  CdrBytes c(true, cdr2);
  c.header(7, 0, "odom").string("base_link").f64(1.5).f64(-2).f64(0);
  c.f64(0).f64(0).f64(0.7071067811865476).f64(0.7071067811865476);
  return c.bytes();
}

TEST(Ros2Messages, OdometryInCdrAndCdr2) {
  EXPECT_NE(odometry(false).size(), odometry(true).size());
  for (bool cdr2 : {false, true}) {
    auto odom = decode_odometry(odometry(cdr2));
    ASSERT_TRUE(odom) << odom.message();
    EXPECT_EQ(odom->child_frame_id, "base_link");
    EXPECT_DOUBLE_EQ(odom->position.x, 1.5);
    EXPECT_DOUBLE_EQ(odom->position.y, -2);
    EXPECT_DOUBLE_EQ(odom->orientation.w, 0.7071067811865476);
  }
}

TEST(Ros2Messages, TfMessage) {
  CdrBytes c;
  c.u32(2);
  for (int i = 0; i < 2; ++i) {
    c.header(1, 0, i == 0 ? "base_link" : "/base_link").string(i == 0 ? "laser" : "imu");
    c.f64(0.2 * i).f64(0).f64(0.1).f64(0).f64(0).f64(0).f64(1);
  }
  auto tf = decode_tf_message(c.bytes());
  ASSERT_TRUE(tf) << tf.message();
  ASSERT_EQ(tf->size(), 2u);
  EXPECT_EQ((*tf)[1].header.frame_id, "/base_link");
  EXPECT_EQ((*tf)[1].child_frame_id, "imu");
  EXPECT_DOUBLE_EQ((*tf)[1].translation.x, 0.2);
}

TEST(Ros2Messages, BrokenMessagesAreRefused) {
  auto scan = laser_scan(true);
  EXPECT_THAT(decode_laser_scan(std::vector<uint8_t>(scan.begin(), scan.end() - 9)).message(),
              HasSubstr("runs past its end"));
  scan[1] = 3;  // parameter list CDR
  EXPECT_THAT(decode_laser_scan(scan).message(), HasSubstr("representation 3"));
  EXPECT_THAT(decode_odometry(std::vector<uint8_t>{0, 1}).message(), HasSubstr("header"));
  CdrBytes no_range;
  no_range.header(1, 0, "l").f32(0).f32(0).f32(0).f32(0).f32(0).f32(0).f32(0).u32(0).u32(0);
  EXPECT_THAT(decode_laser_scan(no_range.bytes()).message(), HasSubstr("range_max"));
  CdrBytes zero_rotation;
  zero_rotation.header(1, 0, "o").string("b").f64(0).f64(0).f64(0).f64(0).f64(0).f64(0).f64(0);
  EXPECT_THAT(decode_odometry(zero_rotation.bytes()).message(), HasSubstr("zero pose"));
  CdrBytes many;
  many.u32(4000000000u);
  EXPECT_FALSE(decode_tf_message(many.bytes()));
  CdrBytes huge_string;
  huge_string.i32(1).u32(0).u32(1000);
  EXPECT_FALSE(decode_laser_scan(huge_string.bytes()));
}

}  // namespace
}  // namespace slam::robot_log
