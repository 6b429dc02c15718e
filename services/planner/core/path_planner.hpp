#pragma once
// The path query front door: checks a request, picks A* or an OMPL planner, reduces the result to
// waypoints and states the outcome as a PlanStatus with a reason a person can act on.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/core/result.hpp"
#include "planner/core/grid_astar.hpp"
#include "planner/core/ompl_planner.hpp"
#include "planner/core/plan_types.hpp"
#include "planner/core/planning_grid.hpp"
#include "planner/core/start_escape.hpp"

namespace slam::planner {

struct PlannerConfig {
  // Goals and path requests plan through unexplored cells (a robot discovers the way as it drives,
  // as Nav2's allow_unknown does); Blocked refuses targets in unexplored space.
  UnknownPolicy unknown = UnknownPolicy::Allowed;
  double unknown_cost_factor = 3.0;  // A* step cost multiplier into unknown cells (>= 1)
  uint32_t ompl_seed = 1;
  // How far one RRT extension reaches (RRTConnect, RRT*); 0 = OMPL's default, a fifth of the map's
  // diagonal. In cluttered rooms a long extension almost always hits something and is thrown away,
  // so a few metres grows the trees faster (docs/performance.md, planner).
  double ompl_range_m = 3.0;
  // FMT*'s sample count: its time grows with it, its path length shrinks (docs/performance.md).
  uint32_t ompl_fmt_samples = 8000;
  // The algorithm robot goals (and exploring robots' legs) are planned with: "astar" or an OMPL
  // planner; OMPL gets goal_time_budget_s, and A* answers when it finds nothing in that time.
  std::string goal_algorithm = "astar";
  double goal_time_budget_s = 0.25;
  double max_time_budget_s = 60.0;  // longer requests are refused, not silently shortened
  // A robot planning its own goal from an inflated or unexplored cell first leaves for the nearest
  // passable cell this close (robot radius + inflation + a margin for pose noise).
  double escape_radius_m = 0.5;
};

// Ok, or the first bad field with the reason.
Status validate(const PlannerConfig& config);

struct PathQuery {
  Vec2 start;
  Vec2 goal;
  std::string algorithm = "astar";  // "astar", "rrtconnect", "rrtstar", "prmstar", "fmtstar"
  double time_budget_s = 1.0;       // used by the OMPL planners; must be positive
};

class PathPlanner {
 public:
  explicit PathPlanner(const PlannerConfig& config);

  // One query on the current grid. Never throws; every failure is a status with a reason.
  PlanResult plan(const PlanningGrid& grid, const PathQuery& query);
  // A path for a robot's own goal (goals and exploration) under `policy`, with A* or `algorithm`
  // (an OMPL planner given goal_time_budget_s; A* answers when it finds nothing in time). A start
  // in an impassable cell leaves through the nearest passable cell within escape_radius_m: the
  // path is then the exact start, that cell's centre, and on. With `snap_goal` an impassable goal
  // is moved the same way (Home: a place the robot once stood on, now maybe inflated).
  PlanResult plan_for_robot(const PlanningGrid& grid, Vec2 start, Vec2 goal, UnknownPolicy policy,
                            bool snap_goal = false, std::string_view algorithm = "astar");
  // The cell a robot at `position` plans from under `policy`: its own, its escape cell, or nothing
  // (the robot is walled in, or nothing around it has been observed yet).
  std::optional<Cell> robot_start(const PlanningGrid& grid, Vec2 position, UnknownPolicy policy);

  const PlannerConfig& config() const { return config_; }

 private:
  // Shared request checks; nothing when the query may run.
  std::optional<PlanResult> reject(const PlanningGrid& grid, const PathQuery& query) const;
  PlanResult run_astar(const PlanningGrid& grid, Cell from, Cell to, Vec2 start, Vec2 goal,
                       UnknownPolicy policy);
  // An OMPL planner from `start` (in cell `from`) to `goal` (in `to`). When it finds nothing in
  // time, A* decides: NO_PATH when it proves there is none, else TIMEOUT, or with
  // `astar_when_out_of_time` A*'s own path.
  PlanResult run_ompl(const PlanningGrid& grid, Cell from, Cell to, Vec2 start, Vec2 goal,
                      std::string_view algorithm, double budget_s, UnknownPolicy policy,
                      bool astar_when_out_of_time);
  double escape_cells(const PlanningGrid& grid) const;

  PlannerConfig config_;
  GridAstar astar_;
  OmplPlanner ompl_;
  StartEscape escape_;
  std::vector<Cell> cells_;
};

}  // namespace slam::planner
