#pragma once
// Sampling-based planners from OMPL ("rrtconnect", "rrtstar", "prmstar", "fmtstar") over the
// planning grid: a 2-D real vector space bounded by the grid, states valid on passable cells, motions
// checked cell by cell (GridMotionValidator), the solution simplified with OMPL's PathSimplifier.
// OMPL planners treat unexplored cells (when the policy allows them) as plain free space: the
// unknown-cost factor is A*'s.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "planner/core/plan_types.hpp"
#include "planner/core/planning_grid.hpp"

namespace slam::planner {

// True for the algorithm names OmplPlanner accepts.
bool is_ompl_algorithm(std::string_view name);

struct OmplOutcome {
  PlanStatus status = PlanStatus::Timeout;  // Ok, or Timeout when no exact solution in budget
  std::string reason;
  std::vector<Vec2> path;  // simplified, start .. goal
};

class OmplPlanner {
 public:
  // Seeds OMPL's global generator (only the first planner in a process can: OMPL ignores later
  // seeds once sampling started) and quiets OMPL's logging to warnings. `range_m` > 0 limits each
  // RRT extension (0: OMPL's default); `fmt_samples` is FMT*'s sample count.
  OmplPlanner(uint32_t seed, double range_m, uint32_t fmt_samples);

  // Plans start -> goal with `algorithm` within `budget_s`: three quarters for solving, the rest
  // (at least one pass) for simplification; FMT* stops when its tree reaches the goal and gets one
  // shortcutting pass. Start and goal must be valid cells; the caller checks.
  OmplOutcome plan(const PlanningGrid& grid, Vec2 start, Vec2 goal, std::string_view algorithm,
                   double budget_s, UnknownPolicy policy) const;

 private:
  double range_m_ = 0.0;
  uint32_t fmt_samples_ = 0;
};

}  // namespace slam::planner
