#pragma once
// The path query front door: checks a request, picks A* or an OMPL planner, reduces the result to
// waypoints and states the outcome as a PlanStatus with a reason a person can act on.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/result.hpp"
#include "planner/grid_astar.hpp"
#include "planner/ompl_planner.hpp"
#include "planner/plan_types.hpp"
#include "planner/planning_grid.hpp"

namespace slam::planner {

struct PlannerConfig {
  UnknownPolicy unknown = UnknownPolicy::Blocked;
  double unknown_cost_factor = 3.0;  // A* step cost multiplier into unknown cells (>= 1)
  uint32_t ompl_seed = 1;
  double max_time_budget_s = 60.0;  // longer requests are refused, not silently shortened
};

// Ok, or the first bad field with the reason.
Status validate(const PlannerConfig& config);

struct PathQuery {
  Vec2 start;
  Vec2 goal;
  std::string algorithm = "astar";  // "astar", "rrtconnect", "rrtstar", "prmstar"
  double time_budget_s = 1.0;       // used by the OMPL planners; must be positive
};

class PathPlanner {
 public:
  explicit PathPlanner(const PlannerConfig& config);

  // One query on the current grid. Never throws; every failure is a status with a reason.
  PlanResult plan(const PlanningGrid& grid, const PathQuery& query);
  // A* between two map points with the configured unknown policy (goals and exploration).
  PlanResult plan_astar(const PlanningGrid& grid, Vec2 start, Vec2 goal);

  const PlannerConfig& config() const { return config_; }

 private:
  // Shared request checks; nothing when the query may run.
  std::optional<PlanResult> reject(const PlanningGrid& grid, const PathQuery& query) const;
  PlanResult run_astar(const PlanningGrid& grid, Vec2 start, Vec2 goal);

  PlannerConfig config_;
  GridAstar astar_;
  OmplPlanner ompl_;
  std::vector<Cell> cells_;
};

}  // namespace slam::planner
