// RobotPositions: newest-wins merge of robot positions (see robot_positions.hpp).
#include "planner/robot_positions.hpp"

namespace slam::planner {

bool RobotPositions::offer(std::string_view robot_id, Vec2 position, int64_t last_seen_ns) {
  auto it = seen_.find(robot_id);
  if (it == seen_.end()) it = seen_.emplace(std::string(robot_id), Seen{}).first;
  Seen& seen = it->second;
  if (last_seen_ns < seen.last_seen_ns) return false;
  seen.last_seen_ns = last_seen_ns;
  if (seen.round == round_) {
    pending_[seen.index].position = position;
    pending_[seen.index].last_seen_ns = last_seen_ns;
    return true;
  }
  seen.round = round_;
  seen.index = pending_.size();
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
  // The entry stays (with its slot in this round, if any) so a robot forgotten and heard again
  // within one round is still taken once.
  if (auto it = seen_.find(robot_id); it != seen_.end()) it->second.last_seen_ns = Seen{}.last_seen_ns;
}

}  // namespace slam::planner
