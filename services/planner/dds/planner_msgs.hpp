#pragma once
// Conversions between the IDL types (Fast DDS generated classes, nav.idl / map.idl / robot.idl)
// and the planner core's types; the fleet's messages and enumerations convert through
// common/fastdds/fleet_messages.hpp. Only the service edge includes this; the core never sees IDL.
// Incoming values are checked here (enums in range, strings non-empty) so the core gets only
// values it can represent; geometry checks (NaN, outside the map) stay with the core.

#include <optional>
#include <string>
#include <vector>

#include "common/core/result.hpp"
#include "common/fastdds/fleet_messages.hpp"
#include "planner/core/goal_tracker.hpp"
#include "planner/core/path_planner.hpp"
#include "planner/core/planning_grid.hpp"

namespace slam::planner {

// Fills `out` (its buffer reused) with the points of `in`.
void to_points(const std::vector<Vec2>& in, std::vector<slam::Point2>& out);

// Replaces `grid` with the snapshot; its cells are moved out of `snapshot`.
Status apply_snapshot(slam::GridSnapshot& snapshot, PlanningGrid& grid);
// Applies the patch when it follows the grid's version; `changed` gets the changed tiles' boxes.
Status apply_patch(const slam::GridTiles& patch, PlanningGrid& grid, std::vector<CellBox>& changed);

struct GoalCommand {
  std::string robot_id;  // one robot or kAllRobots
  Goal goal;
};
Result<GoalCommand> to_goal(const slam::NavGoal& sample);

struct PathJob {
  uint64_t request_id = 0;
  std::string client_id;
  PathQuery query;
};
PathJob to_job(const slam::PathRequest& sample);

// A reply to `job` from `result` (reasons longer than the IDL bound are cut).
void fill_reply(const PathJob& job, const PlanResult& result, slam::PathReply& out);

// The robot's path as the viewer shows it.
void fill_path(const std::string& robot_id, const GoalTracker& tracker, slam::RobotPath& out);

// What a RobotPath (the owner planner's) tells the other planners about its robot.
struct PathReport {
  std::optional<Vec2> frontier;  // where an exploring robot drives (home too, when homing)
  uint64_t goal_id = 0;
  bool finished = false;    // the goal was reached or failed
  std::vector<Vec2> ahead;  // waypoints still to drive to while the goal is active (coordination)
};
PathReport to_report(const msg::RobotPath& path);

}  // namespace slam::planner
