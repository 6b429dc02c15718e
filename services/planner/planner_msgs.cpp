// IDL <-> core conversions for slam-planner. The core's enums mirror the IDL's one to one and in
// the same order (plan_types.hpp, goal_tracker.hpp), so a range check is the whole translation.
#include "planner/planner_msgs.hpp"

#include <string>

namespace slam::planner {

slam::Point2 to_point(Vec2 v) {
  slam::Point2 p;
  p.x(v.x);
  p.y(v.y);
  return p;
}

void to_points(const std::vector<Vec2>& in, std::vector<slam::Point2>& out) {
  out.clear();
  out.reserve(in.size());
  for (const Vec2& v : in) out.push_back(to_point(v));
}

Status apply_snapshot(slam::GridSnapshot& snapshot, PlanningGrid& grid) {
  const slam::GridInfo& info = snapshot.info();
  if (info.width() > static_cast<uint32_t>(INT32_MAX) || info.height() > static_cast<uint32_t>(INT32_MAX)) {
    return Error{"grid snapshot is too large: " + std::to_string(info.width()) + "x" +
                 std::to_string(info.height())};
  }
  const GridGeometry geometry{to_vec2(info.origin()), info.resolution(), static_cast<int32_t>(info.width()),
                              static_cast<int32_t>(info.height())};
  return grid.reset(geometry, snapshot.layout_id(), snapshot.version(), std::move(snapshot.cells()));
}

Status apply_patch(const slam::GridTiles& patch, PlanningGrid& grid, std::vector<CellBox>& changed) {
  const TilePatchView view{patch.tile_side(), patch.encoding(), patch.tiles(), patch.data()};
  return grid.apply_patch(patch.layout_id(), patch.version(), view, changed);
}

Result<GoalCommand> to_goal(const slam::NavGoal& sample) {
  GoalCommand out;
  out.robot_id = sample.robot_id().to_string();
  if (out.robot_id.empty())
    return Error{"goal " + std::to_string(sample.goal_id()) + " has an empty robot_id"};
  const auto mode = static_cast<uint32_t>(sample.mode());
  if (mode > static_cast<uint32_t>(slam::GOAL_STOP)) {
    return Error{"goal " + std::to_string(sample.goal_id()) + " has unknown mode " + std::to_string(mode)};
  }
  const auto anchor = static_cast<uint32_t>(sample.square_anchor());
  if (anchor > static_cast<uint32_t>(slam::SQUARE_CENTRED)) {
    return Error{"goal " + std::to_string(sample.goal_id()) + " has unknown square anchor " +
                 std::to_string(anchor)};
  }
  out.goal.goal_id = sample.goal_id();
  out.goal.mode = static_cast<GoalMode>(mode);
  out.goal.target = to_vec2(sample.target());
  out.goal.square_size = sample.square_size();
  out.goal.square_anchor = static_cast<SquareAnchor>(anchor);
  return out;
}

PathJob to_job(const slam::PathRequest& sample) {
  PathJob job;
  job.request_id = sample.request_id();
  job.client_id = sample.client_id().to_string();
  job.query.start = to_vec2(sample.start());
  job.query.goal = to_vec2(sample.goal());
  job.query.algorithm = sample.algorithm().to_string();
  job.query.time_budget_s = sample.time_budget_s();
  return job;
}

slam::PlanStatus to_idl(PlanStatus status) {
  return static_cast<slam::PlanStatus>(static_cast<uint32_t>(status));
}

void fill_reply(const PathJob& job, const PlanResult& result, slam::PathReply& out) {
  out.request_id(job.request_id);
  out.client_id(job.client_id);
  out.status(to_idl(result.status));
  out.reason(result.reason);
  to_points(result.path, out.path());
  out.length_m(result.length_m);
  out.planning_time_s(result.planning_time_s);
}

void fill_path(const std::string& robot_id, const GoalTracker& tracker, slam::RobotPath& out) {
  out.robot_id(robot_id);
  out.goal_id(tracker.goal().goal_id);
  out.mode(static_cast<slam::GoalMode>(static_cast<uint32_t>(tracker.mode())));
  out.status(static_cast<slam::GoalStatus>(static_cast<uint32_t>(tracker.status())));
  out.target(to_point(tracker.target()));
  to_points(tracker.waypoints(), out.waypoints());
  out.current(static_cast<uint32_t>(tracker.current_index()));
  out.reason(tracker.reason());
}

PathReport to_report(const slam::RobotPath& sample) {
  PathReport out;
  out.goal_id = sample.goal_id();
  out.finished = sample.status() == slam::GOAL_STATUS_REACHED || sample.status() == slam::GOAL_STATUS_FAILED;
  // A robot between frontiers has no waypoints; one homing is not told apart (its home is claimed).
  if (sample.mode() == slam::GOAL_EXPLORE && sample.status() == slam::GOAL_STATUS_ACTIVE &&
      !sample.waypoints().empty()) {
    out.frontier = to_vec2(sample.target());
  }
  if (sample.status() == slam::GOAL_STATUS_ACTIVE) {
    const auto& w = sample.waypoints();
    for (size_t i = sample.current(); i < w.size(); ++i) out.ahead.push_back(to_vec2(w[i]));
  }
  return out;
}

}  // namespace slam::planner
