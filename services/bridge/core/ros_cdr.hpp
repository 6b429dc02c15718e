#pragma once
// The map as ROS 2 sends it over DDS, for the Foxglove face's nav_msgs/msg/OccupancyGrid channel
// (message encoding "cdr", schema encoding "ros2msg"): plain CDR, little endian, with its 4-byte
// encapsulation header, and the message definition with its dependencies in ros2msg's one-text form.
#include <string>

#include "bridge/core/ros_face.hpp"

namespace slam::bridge {

inline constexpr const char* kOccupancyGridType = "nav_msgs/msg/OccupancyGrid";

// The definitions of nav_msgs/msg/OccupancyGrid and every type it uses, each dependency after a
// separator line and "MSG: package/Type".
extern const char* const kOccupancyGridDefinition;

std::string occupancy_grid_cdr(const OccupancyGridOut& grid);

}  // namespace slam::bridge
