#pragma once
// What an operator asks of the fleet through a client: a goal published on the goal channel, and a
// path service call; parsed from and answered in JSON. Plain C++: the DDS edge turns them into
// NavGoal and PathRequest; the planner's PathReply comes back as the fleet's plain message.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/core/fleet_messages.hpp"
#include "common/core/geometry.hpp"
#include "common/core/result.hpp"

namespace slam::bridge {

// {"robot_id": "sim-1", "x": 2.0, "y": 1.5, "mode": "planned"}: mode is optional (planned); x and y
// are needed by planned and direct goals only. robot_id "*" addresses every robot. An operator may
// send every goal mode but the calibration square.
struct GoalCommand {
  std::string robot_id;
  msg::GoalMode mode = msg::GoalMode::Planned;
  Vec2 target;
};

Result<GoalCommand> parse_goal(std::string_view json_text);

// {"start": {"x": 0, "y": 0}, "goal": {"x": 3, "y": 1}, "algorithm": "astar", "time_budget_s": 1.0}:
// algorithm and time budget are optional.
struct PathQuery {
  Vec2 start;
  Vec2 goal;
  std::string algorithm = "astar";
  double time_budget_s = 1.0;
};

Result<PathQuery> parse_path_query(std::string_view json_text);

// The planner's answer in the response schema's fields, its status as the schema names it ("ok",
// "no_path", ...).
std::string path_answer_json(const msg::PathReply& answer);

}  // namespace slam::bridge
