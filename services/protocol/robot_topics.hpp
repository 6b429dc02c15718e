#pragma once
// Topics as a robot sees them (the gateway's view is topic.hpp): where a robot publishes, and which
// server -> robot topic an inbound command arrived on. A client speaking for many robots at once
// (the simulator's multiplexed mode) subscribes the filters below and learns the robot from the topic.
#include <cstdint>
#include <string>
#include <string_view>

#include "protocol/reject_reason.hpp"

namespace slam::protocol {

// Server -> robot subscription filters for every robot at once.
inline constexpr std::string_view kV1CommandFilter = "v1/server/+/cmd";
inline constexpr std::string_view kV2WaypointFilter = "v2/server/+/waypoint";
inline constexpr std::string_view kV2PathFilter = "v2/server/+/path";

// Robot -> server topics; BadRobotId (and `out` untouched) when the id is invalid. `out` keeps capacity.
CodecStatus v1_adv_topic(std::string_view robot_id, std::string& out);
CodecStatus v2_pose_topic(std::string_view robot_id, std::string& out);
CodecStatus v2_scan_topic(std::string_view robot_id, std::string& out);
CodecStatus v2_status_topic(std::string_view robot_id, std::string& out);

enum class CommandKind : std::uint8_t { V1Waypoint, V2Waypoint, V2Path };

struct ParsedCommandTopic {
  CommandKind kind = CommandKind::V1Waypoint;
  std::string_view robot_id;  // points into the parsed topic
};

// Classifies v1/server/<id>/cmd, v2/server/<id>/waypoint and v2/server/<id>/path. UnknownTopic for
// anything else, BadRobotId when the id level fails validate_robot_id().
CodecStatus parse_command_topic(std::string_view topic, ParsedCommandTopic& out);

}  // namespace slam::protocol
