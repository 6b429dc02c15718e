// IDL <-> core conversions for slam-planner. The core's enums are the fleet's
// (common/core/fleet_messages.hpp), so a range check and common/fastdds' conversion are the whole
// translation.
#include "planner/dds/planner_msgs.hpp"

#include <string>

namespace slam::planner {

void to_points(const std::vector<Vec2>& in, std::vector<slam::Point2>& out) {
  out.clear();
  out.reserve(in.size());
  for (const Vec2& v : in) out.push_back(msg::to_idl(v));
}

Status apply_snapshot(slam::GridSnapshot& snapshot, PlanningGrid& grid) {
  const slam::GridInfo& info = snapshot.info();
  if (info.width() > static_cast<uint32_t>(INT32_MAX) || info.height() > static_cast<uint32_t>(INT32_MAX)) {
    return Error{"grid snapshot is too large: " + std::to_string(info.width()) + "x" +
                 std::to_string(info.height())};
  }
  const GridGeometry geometry{msg::from_idl(info.origin()), info.resolution(),
                              static_cast<int32_t>(info.width()), static_cast<int32_t>(info.height())};
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
  out.goal.mode = msg::from_idl(sample.mode());
  out.goal.target = msg::from_idl(sample.target());
  out.goal.square_size = sample.square_size();
  out.goal.square_anchor = msg::from_idl(sample.square_anchor());
  return out;
}

PathJob to_job(const slam::PathRequest& sample) {
  PathJob job;
  job.request_id = sample.request_id();
  job.client_id = sample.client_id().to_string();
  job.query.start = msg::from_idl(sample.start());
  job.query.goal = msg::from_idl(sample.goal());
  job.query.algorithm = sample.algorithm().to_string();
  job.query.time_budget_s = sample.time_budget_s();
  return job;
}

void fill_reply(const PathJob& job, const PlanResult& result, slam::PathReply& out) {
  out.request_id(job.request_id);
  out.client_id(job.client_id);
  out.status(msg::to_idl(result.status));
  out.reason(result.reason);
  to_points(result.path, out.path());
  out.length_m(result.length_m);
  out.planning_time_s(result.planning_time_s);
}

void fill_path(const std::string& robot_id, const GoalTracker& tracker, slam::RobotPath& out) {
  out.robot_id(robot_id);
  out.goal_id(tracker.goal().goal_id);
  out.mode(msg::to_idl(tracker.mode()));
  out.status(msg::to_idl(tracker.status()));
  out.target(msg::to_idl(tracker.target()));
  to_points(tracker.waypoints(), out.waypoints());
  out.current(static_cast<uint32_t>(tracker.current_index()));
  out.reason(tracker.reason());
}

PathReport to_report(const msg::RobotPath& path) {
  PathReport out;
  out.goal_id = path.goal_id;
  out.finished = path.status == GoalStatus::Reached || path.status == GoalStatus::Failed;
  // A robot between frontiers has no waypoints; one homing is not told apart (its home is claimed).
  if (path.mode == GoalMode::Explore && path.status == GoalStatus::Active && !path.waypoints.empty())
    out.frontier = path.target;
  if (path.status == GoalStatus::Active) {
    const auto& w = path.waypoints;
    for (size_t i = path.current; i < w.size(); ++i) out.ahead.push_back(w[i]);
  }
  return out;
}

}  // namespace slam::planner
