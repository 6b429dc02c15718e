#pragma once
// Where a laser sits on the robot, from the static transforms a ROS 2 recording keeps (/tf_static):
// the chain of transforms from the robot's base frame (the odometry's child_frame_id) down to the
// scan's frame, composed in 3-D and laid flat. A laser mounted upside down (its z axis pointing
// down) sees the world mirrored; `mirrored` says so, and the caller reverses the beams.
#include <optional>
#include <string>
#include <unordered_map>

#include "common/core/geometry.hpp"
#include "simulator/robot_log/ros2_messages.hpp"

namespace slam::robot_log {

struct LaserMount {
  Pose in_robot;  // x, y and heading of the laser in the base frame
  bool mirrored = false;
};

class StaticFrames {
 public:
  // Keeps the transform to each child frame (a later one for the same child replaces it).
  void add(const Ros2Transform& transform);
  // The laser frame in the base frame; nothing when no chain of known transforms links them.
  // Frame names compare without a leading '/' (ROS 1 habit).
  std::optional<LaserMount> mount(const std::string& base_frame, const std::string& laser_frame) const;
  bool empty() const { return parent_of_.empty(); }

 private:
  struct Link {
    std::string parent;
    Vec3d translation;
    Quaternion rotation;
  };
  std::unordered_map<std::string, Link> parent_of_;  // by child frame
};

}  // namespace slam::robot_log
