#pragma once
// Reading a ROS 2 recording (rosbag2's MCAP: message encoding "cdr") into a RobotLog: every
// sensor_msgs/msg/LaserScan on the scan topic, in file order, paired with the nav_msgs/msg/Odometry
// pose interpolated at its header stamp, and placed on the robot by /tf_static when it links the
// odometry's child frame to the scan's frame (else the laser sits at the robot's centre).
//
// Stats count messages as lines: scans kept, odometry messages, messages on other topics as
// unknown kinds, and as bad lines the messages that do not decode and the scans with no odometry
// within max_odometry_gap_s of their stamp.
#include <filesystem>
#include <string>

#include "common/core/mcap_reader.hpp"
#include "common/core/result.hpp"
#include "simulator/robot_log/robot_log.hpp"

namespace slam::robot_log {

struct Ros2McapOptions {
  std::string scan_topic;  // empty: the recording's only LaserScan topic
  std::string odom_topic;  // empty: its only Odometry topic
  double max_odometry_gap_s = 0.5;

  Status validate() const;
};

// The scans of an already parsed MCAP file (the data its messages point into must outlive the call).
Result<RobotLog> ros2_log_from_mcap(const mcap::Contents& contents, const Ros2McapOptions& options = {});

Result<RobotLog> read_ros2_mcap_log(const std::filesystem::path& path, const Ros2McapOptions& options = {});

}  // namespace slam::robot_log
