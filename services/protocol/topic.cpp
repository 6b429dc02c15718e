// Topic classification and robot id validation: the first gate every inbound message passes.
#include "protocol/topic.hpp"

#include <array>
#include <string>

#include "protocol/codec_types.hpp"
#include "protocol/text_check.hpp"

namespace slam::protocol {
namespace {

constexpr std::string_view kV1Prefix = "v1/robot/";
constexpr std::string_view kV2Prefix = "v2/robot/";
static_assert(kV1Prefix.size() == kV2Prefix.size(), "parse_topic strips either prefix by one length");

struct KindName {
  std::string_view level;  // last topic level
  TopicKind kind;
};
constexpr std::array<KindName, 4> kV2Kinds = {{{"pose", TopicKind::V2Pose},
                                               {"points", TopicKind::V2Points},
                                               {"scan", TopicKind::V2Scan},
                                               {"status", TopicKind::V2Status}}};

CodecStatus unknown(std::string_view topic) {
  return {RejectReason::UnknownTopic, "topic '" + escape_for_log(topic) +
                                          "' is not v1/robot/<id>/adv or "
                                          "v2/robot/<id>/{pose,points,scan,status}"};
}

}  // namespace

CodecStatus build_robot_topic(std::string_view robot_id, std::string_view prefix, std::string_view suffix,
                              std::string& out) {
  if (auto status = validate_robot_id(robot_id); !status) return status;
  out.assign(prefix);
  out.append(robot_id);
  out.append(suffix);
  return CodecStatus::ok();
}

std::string_view topic_kind_name(TopicKind kind) {
  switch (kind) {
    case TopicKind::V1Adv:
      return "v1_adv";
    case TopicKind::V2Pose:
      return "v2_pose";
    case TopicKind::V2Points:
      return "v2_points";
    case TopicKind::V2Scan:
      return "v2_scan";
    case TopicKind::V2Status:
      return "v2_status";
  }
  return "unknown";
}

CodecStatus validate_robot_id(std::string_view robot_id) {
  if (robot_id.empty()) return {RejectReason::BadRobotId, "robot id is empty"};
  if (robot_id.size() > kMaxRobotIdBytes)
    return {RejectReason::BadRobotId, "robot id is " + std::to_string(robot_id.size()) + " bytes, limit " +
                                          std::to_string(kMaxRobotIdBytes)};
  if (robot_id == "*") return {RejectReason::BadRobotId, "robot id '*' is reserved for 'every robot'"};
  if (const auto at = robot_id.find_first_of("+#/"); at != std::string_view::npos)
    return {RejectReason::BadRobotId, "robot id '" + escape_for_log(robot_id) + "' contains '" +
                                          std::string(1, robot_id[at]) + "' at byte " + std::to_string(at)};
  if (const auto problem = find_text_problem(robot_id))
    return {RejectReason::BadRobotId, "robot id '" + escape_for_log(robot_id) + "' has " +
                                          std::string(problem->what) + " at byte " +
                                          std::to_string(problem->offset)};
  return CodecStatus::ok();
}

CodecStatus parse_topic(std::string_view topic, ParsedTopic& out) {
  const bool v1 = topic.starts_with(kV1Prefix);
  if (!v1 && !topic.starts_with(kV2Prefix)) return unknown(topic);
  // The id is everything between the prefix and the last '/', so "v1/robot/a/b/adv" is a bad id
  // ("a/b" contains '/') rather than an unknown topic: the sender is clearly a robot.
  const std::string_view rest = topic.substr(kV1Prefix.size());
  const auto slash = rest.rfind('/');
  if (slash == std::string_view::npos) return unknown(topic);
  const std::string_view id = rest.substr(0, slash);
  const std::string_view level = rest.substr(slash + 1);

  TopicKind kind = TopicKind::V1Adv;
  if (v1) {
    if (level != "adv") return unknown(topic);
  } else {
    bool found = false;
    for (const auto& k : kV2Kinds) {
      if (k.level == level) {
        kind = k.kind;
        found = true;
      }
    }
    if (!found) return unknown(topic);
  }
  if (auto status = validate_robot_id(id); !status) return status;
  out.kind = kind;
  out.robot_id = id;
  return CodecStatus::ok();
}

CodecStatus v1_command_topic(std::string_view robot_id, std::string& out) {
  return build_robot_topic(robot_id, "v1/server/", "/cmd", out);
}
CodecStatus v2_waypoint_topic(std::string_view robot_id, std::string& out) {
  return build_robot_topic(robot_id, "v2/server/", "/waypoint", out);
}
CodecStatus v2_path_topic(std::string_view robot_id, std::string& out) {
  return build_robot_topic(robot_id, "v2/server/", "/path", out);
}

}  // namespace slam::protocol
