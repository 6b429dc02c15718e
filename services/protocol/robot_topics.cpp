// Robot-side topic names, built and parsed with the same robot id rules as the gateway's topics.
#include "protocol/robot_topics.hpp"

#include "protocol/text_check.hpp"
#include "protocol/topic.hpp"

namespace slam::protocol {
namespace {

struct CommandTopic {
  std::string_view prefix;
  std::string_view level;
  CommandKind kind;
};
constexpr CommandTopic kCommandTopics[] = {{"v1/server/", "cmd", CommandKind::V1Waypoint},
                                           {"v2/server/", "waypoint", CommandKind::V2Waypoint},
                                           {"v2/server/", "path", CommandKind::V2Path}};

}  // namespace

CodecStatus v1_adv_topic(std::string_view robot_id, std::string& out) {
  return build_robot_topic(robot_id, "v1/robot/", "/adv", out);
}
CodecStatus v2_pose_topic(std::string_view robot_id, std::string& out) {
  return build_robot_topic(robot_id, "v2/robot/", "/pose", out);
}
CodecStatus v2_scan_topic(std::string_view robot_id, std::string& out) {
  return build_robot_topic(robot_id, "v2/robot/", "/scan", out);
}
CodecStatus v2_status_topic(std::string_view robot_id, std::string& out) {
  return build_robot_topic(robot_id, "v2/robot/", "/status", out);
}

CodecStatus parse_command_topic(std::string_view topic, ParsedCommandTopic& out) {
  // As in parse_topic(): the id is everything between the prefix and the last '/'.
  const auto slash = topic.rfind('/');
  if (slash != std::string_view::npos) {
    const std::string_view level = topic.substr(slash + 1);
    for (const auto& t : kCommandTopics) {
      if (level != t.level || !topic.starts_with(t.prefix) || slash < t.prefix.size()) continue;
      const std::string_view id = topic.substr(t.prefix.size(), slash - t.prefix.size());
      if (auto status = validate_robot_id(id); !status) return status;
      out.kind = t.kind;
      out.robot_id = id;
      return CodecStatus::ok();
    }
  }
  return {RejectReason::UnknownTopic, "topic '" + escape_for_log(topic) +
                                          "' is not v1/server/<id>/cmd or v2/server/<id>/{waypoint,path}"};
}

}  // namespace slam::protocol
