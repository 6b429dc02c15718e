// RobotPositions: the newest position per robot since the last take (see robot_positions.hpp).
#include "planner/core/robot_positions.hpp"

namespace slam::planner {

bool RobotPositions::offer(std::string_view robot_id, Vec2 position, int64_t last_seen_ns) {
  if (stamps_.judge(robot_id, last_seen_ns) != LatestStamps::Verdict::Fresh) return false;
  auto it = slots_.find(robot_id);
  if (it == slots_.end()) it = slots_.emplace(std::string(robot_id), Slot{}).first;
  Slot& slot = it->second;
  if (slot.round == round_) {
    pending_[slot.index].position = position;
    pending_[slot.index].last_seen_ns = last_seen_ns;
    return true;
  }
  slot.round = round_;
  slot.index = pending_.size();
  RobotPosition& p = pending_.emplace_back();
  p.robot_id.assign(robot_id);
  p.position = position;
  p.last_seen_ns = last_seen_ns;
  return true;
}

void RobotPositions::take(std::vector<RobotPosition>& out) {
  out.swap(pending_);
  pending_.clear();
  ++round_;
}

void RobotPositions::forget(std::string_view robot_id) {
  stamps_.forget(robot_id);
  const auto it = slots_.find(robot_id);
  if (it == slots_.end()) return;
  const Slot gone = it->second;
  slots_.erase(it);
  if (gone.round != round_) return;
  // Rare (an operator's forget): close the gap and move the later slots of this round down.
  pending_.erase(pending_.begin() + static_cast<std::ptrdiff_t>(gone.index));
  for (auto& [id, slot] : slots_)
    if (slot.round == round_ && slot.index > gone.index) --slot.index;
}

}  // namespace slam::planner
