#pragma once
// The three ROS 2 message types a robot recording needs, decoded from CDR into plain structs with
// only the fields used: sensor_msgs/msg/LaserScan, nav_msgs/msg/Odometry (its pose) and
// tf2_msgs/msg/TFMessage (where the laser sits on the robot, from /tf_static).
#include <span>
#include <string>
#include <vector>

#include "common/core/result.hpp"

namespace slam::robot_log {

inline constexpr const char* kLaserScanType = "sensor_msgs/msg/LaserScan";
inline constexpr const char* kOdometryType = "nav_msgs/msg/Odometry";
inline constexpr const char* kTfMessageType = "tf2_msgs/msg/TFMessage";

struct Vec3d {
  double x = 0, y = 0, z = 0;
};
struct Quaternion {
  double x = 0, y = 0, z = 0, w = 1;
};

struct Ros2Header {
  double stamp_s = 0;  // sec + nanosec
  std::string frame_id;
};

struct Ros2LaserScan {
  Ros2Header header;
  float angle_min = 0, angle_max = 0, angle_increment = 0;
  float range_min = 0, range_max = 0;
  std::vector<float> ranges;
};

struct Ros2Odometry {
  Ros2Header header;
  std::string child_frame_id;
  Vec3d position;
  Quaternion orientation;
};

struct Ros2Transform {
  Ros2Header header;  // header.frame_id: the parent
  std::string child_frame_id;
  Vec3d translation;
  Quaternion rotation;
};

Result<Ros2LaserScan> decode_laser_scan(std::span<const uint8_t> cdr);
Result<Ros2Odometry> decode_odometry(std::span<const uint8_t> cdr);
Result<std::vector<Ros2Transform>> decode_tf_message(std::span<const uint8_t> cdr);

}  // namespace slam::robot_log
