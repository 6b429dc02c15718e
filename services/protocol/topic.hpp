#pragma once
// The MQTT topic trees the gateway speaks (see docs/protocol.md):
//   robot -> server  v1/robot/<id>/adv            v2/robot/<id>/{pose,points,scan,status}
//   server -> robot  v1/server/<id>/cmd           v2/server/<id>/{waypoint,path}
// The robot id is the topic level between the tree prefix and the message kind.
#include <cstdint>
#include <string>
#include <string_view>

#include "protocol/reject_reason.hpp"

namespace slam::protocol {

enum class TopicKind : std::uint8_t { V1Adv, V2Pose, V2Points, V2Scan, V2Status };

constexpr bool is_v1(TopicKind kind) {
  return kind == TopicKind::V1Adv;
}
// "v1_adv", "v2_pose", "v2_points", "v2_scan", "v2_status".
std::string_view topic_kind_name(TopicKind kind);

// Subscription filters covering everything parse_topic() accepts.
inline constexpr std::string_view kV1RobotFilter = "v1/robot/+/adv";
inline constexpr std::string_view kV2RobotFilter = "v2/robot/+/+";

struct ParsedTopic {
  TopicKind kind = TopicKind::V1Adv;
  std::string_view robot_id;  // points into the parsed topic: copy it before the topic dies
};

// Classifies an inbound topic. UnknownTopic for anything outside the robot trees (or an unknown
// v2 kind); BadRobotId when the tree and kind match but the id level fails validate_robot_id().
CodecStatus parse_topic(std::string_view topic, ParsedTopic& out);

// A robot id is 1..64 bytes of UTF-8 with no '+', '#', '/' and no control characters, and is not
// "*" (which addresses every robot in NavGoal).
CodecStatus validate_robot_id(std::string_view robot_id);

// prefix + robot_id + suffix after validate_robot_id(); the builders below and in robot_topics.hpp.
CodecStatus build_robot_topic(std::string_view robot_id, std::string_view prefix, std::string_view suffix,
                              std::string& out);

// Outbound topics; BadRobotId (and `out` untouched) when the id is invalid. `out` keeps capacity.
CodecStatus v1_command_topic(std::string_view robot_id, std::string& out);
CodecStatus v2_waypoint_topic(std::string_view robot_id, std::string& out);
CodecStatus v2_path_topic(std::string_view robot_id, std::string& out);

}  // namespace slam::protocol
