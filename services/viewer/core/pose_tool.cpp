// Press, drag, release -> InitialPose (see pose_tool.hpp).
#include "viewer/core/pose_tool.hpp"

#include <cmath>

namespace slam::viewer {

Status PoseTool::arm(const std::string& robot_id) {
  if (robot_id.empty() || robot_id == "*") return Error{"set pose: select one robot first"};
  robot_id_ = robot_id;
  press_.reset();
  return {};
}

void PoseTool::press(Vec2 world) {
  if (!armed()) return;
  press_ = world;
  cursor_ = world;
}

void PoseTool::drag(Vec2 world) {
  if (press_) cursor_ = world;
}

std::optional<InitialPoseCommand> PoseTool::release(Vec2 world, double min_drag_m) {
  if (!press_) return std::nullopt;
  const Vec2 from = *press_;
  press_.reset();
  const Vec2 d = world - from;
  if (!(std::hypot(d.x, d.y) >= min_drag_m)) return std::nullopt;
  InitialPoseCommand c{robot_id_, {from.x, from.y, std::atan2(d.y, d.x)}};
  robot_id_.clear();
  return c;
}

void PoseTool::cancel() {
  robot_id_.clear();
  press_.reset();
}

std::optional<PoseTool::Arrow> PoseTool::arrow() const {
  if (!press_) return std::nullopt;
  return Arrow{*press_, cursor_};
}

}  // namespace slam::viewer
