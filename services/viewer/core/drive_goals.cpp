// Drive tab goals (see drive_goals.hpp).
#include "viewer/core/drive_goals.hpp"

#include <cstdio>

#include "common/core/square_path.hpp"

namespace slam::viewer {

GoalCommand drive_goal(const DriveSettings& s, GoalMode mode) {
  return GoalCommand{s.robot_id, mode, s.target, s.square_size, s.square_centred};
}

std::array<GoalCommand, 4> corner_goals(const DriveSettings& s, bool planned) {
  const std::array<Vec2, 4> corners = square_corners(s.target, s.square_size, s.square_centred);
  std::array<GoalCommand, 4> goals;
  for (size_t i = 0; i < corners.size(); ++i)
    goals[i] = GoalCommand{s.robot_id, planned ? GoalMode::Planned : GoalMode::Direct, corners[i],
                           s.square_size, s.square_centred};
  return goals;
}

std::string describe(const GoalCommand& g) {
  char what[128];
  switch (g.mode) {
    case GoalMode::Direct:
    case GoalMode::Planned:
      std::snprintf(what, sizeof what, "%s goal to (%.2f, %.2f)", goal_mode_name(g.mode), g.target.x,
                    g.target.y);
      break;
    case GoalMode::Square:
      std::snprintf(what, sizeof what, "square goal (%.2f m, %s (%.2f, %.2f))", g.square_size,
                    g.square_centred ? "centred on" : "first corner at", g.target.x, g.target.y);
      break;
    default:
      std::snprintf(what, sizeof what, "%s goal", goal_mode_name(g.mode));
      break;
  }
  return std::string(what) + " for " + (g.robot_id == "*" ? std::string("every robot") : g.robot_id);
}

}  // namespace slam::viewer
