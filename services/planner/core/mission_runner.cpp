// MissionRunner: which leg of a mission comes next.
#include "planner/core/mission_runner.hpp"

#include <cmath>

namespace slam::planner {

Status validate(const Mission& mission, const MissionProgress& progress) {
  const size_t n = mission.waypoints.size();
  if (n == 0) return Error{"a mission needs at least one waypoint"};
  if (n > kMaxMissionWaypoints)
    return Error{"a mission has at most " + std::to_string(kMaxMissionWaypoints) + " waypoints, got " +
                 std::to_string(n)};
  if (mission.loop && n < 2) return Error{"a looped mission needs at least two waypoints"};
  for (size_t i = 0; i < n; ++i) {
    if (!std::isfinite(mission.waypoints[i].x) || !std::isfinite(mission.waypoints[i].y))
      return Error{"mission waypoint " + std::to_string(i) + " is not finite"};
  }
  if (progress.current >= n)
    return Error{"mission current waypoint " + std::to_string(progress.current) + " is past its " +
                 std::to_string(n) + " waypoints"};
  return Status::ok();
}

Goal leg_goal(const Mission& mission, const MissionProgress& progress) {
  Goal goal;
  goal.goal_id = mission.mission_id;
  goal.mode = GoalMode::Planned;
  goal.target = mission.waypoints[progress.current];
  return goal;
}

Goal MissionRunner::start(const std::string& robot_id, const Mission& mission,
                          const MissionProgress& progress) {
  missions_[robot_id] = Running{mission, progress, 0};
  changed_.insert(robot_id);
  return leg_goal(mission, progress);
}

void MissionRunner::end(Running& r, MissionStatus status, const std::string& reason) {
  r.progress.status = status;
  if (!reason.empty()) r.progress.reason = reason;
}

bool MissionRunner::cancel(const std::string& robot_id) {
  const auto it = missions_.find(robot_id);
  if (it == missions_.end() || it->second.progress.status != MissionStatus::Active) return false;
  end(it->second, MissionStatus::Cancelled, "replaced by a goal");
  changed_.insert(robot_id);
  return true;
}

void MissionRunner::forget(const std::string& robot_id) {
  missions_.erase(robot_id);
  changed_.erase(robot_id);
}

std::vector<std::string> MissionRunner::cancel_all() {
  std::vector<std::string> out;
  for (const auto& [id, r] : missions_)
    if (r.progress.status == MissionStatus::Active) out.push_back(id);
  for (const std::string& id : out) cancel(id);
  return out;
}

std::optional<Goal> MissionRunner::leg_ended(const std::string& robot_id, bool reached,
                                             const std::string& reason) {
  const auto it = missions_.find(robot_id);
  if (it == missions_.end() || it->second.progress.status != MissionStatus::Active) return std::nullopt;
  Running& r = it->second;
  MissionProgress& p = r.progress;
  const size_t n = r.mission.waypoints.size();
  changed_.insert(robot_id);
  ++r.legs_in_pass;
  if (reached) {
    r.failures_in_row = 0;
    ++r.reached_in_pass;
  } else {
    ++r.failures_in_row;
    p.reason = "waypoint " + std::to_string(p.current) + " skipped: " + reason;
    if (r.failures_in_row >= n) {
      end(r, MissionStatus::Failed, "no waypoint reachable: " + reason);
      return std::nullopt;
    }
  }
  if (p.current + 1 < n) {
    ++p.current;
    return leg_goal(r.mission, p);
  }
  ++p.laps;
  if (!r.mission.loop) {
    end(r, MissionStatus::Done, "");
    return std::nullopt;
  }
  // Judged on whole passes only: one resumed or adopted mid-way is not.
  const bool stuck = r.legs_in_pass == n && r.reached_in_pass < 2;
  r.legs_in_pass = 0;
  r.reached_in_pass = 0;
  if (stuck) {
    end(r, MissionStatus::Failed, "fewer than two waypoints reachable in a pass (" + p.reason + ")");
    return std::nullopt;
  }
  p.current = 0;
  return leg_goal(r.mission, p);
}

std::optional<Goal> MissionRunner::adopt(const std::string& robot_id, const MissionProgress& progress) {
  const auto it = missions_.find(robot_id);
  if (it == missions_.end() || it->second.progress == progress) return std::nullopt;
  Running& r = it->second;
  const bool moved = r.progress.current != progress.current;
  r.progress = progress;
  r.failures_in_row = 0;
  r.legs_in_pass = 0;
  r.reached_in_pass = 0;
  changed_.insert(robot_id);
  if (!moved || progress.status != MissionStatus::Active) return std::nullopt;
  return leg_goal(r.mission, r.progress);
}

const MissionRunner::Running* MissionRunner::find(const std::string& robot_id) const {
  const auto it = missions_.find(robot_id);
  return it == missions_.end() ? nullptr : &it->second;
}

bool MissionRunner::active(const std::string& robot_id) const {
  const Running* r = find(robot_id);
  return r != nullptr && r->progress.status == MissionStatus::Active;
}

std::vector<std::string> MissionRunner::take_changed() {
  std::vector<std::string> out(changed_.begin(), changed_.end());
  changed_.clear();
  return out;
}

}  // namespace slam::planner
