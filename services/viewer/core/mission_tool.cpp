// The mission tool's draft (see mission_tool.hpp).
#include "viewer/core/mission_tool.hpp"

namespace slam::viewer {

Status MissionTool::add(Vec2 world) {
  if (waypoints_.size() >= kMaxMissionWaypoints)
    return Error{"a mission has at most " + std::to_string(kMaxMissionWaypoints) + " waypoints"};
  waypoints_.push_back(world);
  return Status::ok();
}

void MissionTool::undo() {
  if (!waypoints_.empty()) waypoints_.pop_back();
}

Result<MissionCommand> MissionTool::command(const std::string& robot_id) const {
  if (robot_id.empty() || robot_id == "*") return Error{"select one robot for the mission"};
  if (waypoints_.empty()) return Error{"click on the map to add waypoints first"};
  if (loop_ && waypoints_.size() < 2) return Error{"a looped mission needs at least two waypoints"};
  return MissionCommand{robot_id, waypoints_, loop_};
}

}  // namespace slam::viewer
