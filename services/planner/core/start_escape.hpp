#pragma once
// A robot is always somewhere it physically fits, yet its own cell can be off limits to the
// planner: the mapper inflates walls by the robot radius (a robot brushing a wall stands in an
// inflated cell) and the cells under a robot may not have been observed yet. Planning from there
// begins with a short escape leg to the nearest passable cell close by, found by a breadth-first
// search that never crosses a wall (an occupied cell).
#include <cstdint>
#include <optional>
#include <vector>

#include "planner/core/plan_types.hpp"
#include "planner/core/planning_grid.hpp"

namespace slam::planner {

class StartEscape {
 public:
  // The passable cell (under `policy`) nearest to `from` (centre to centre), among the cells
  // within `radius_cells` that an 8-connected walk from `from` reaches without entering an
  // occupied cell or cutting between two. `from` itself when it is passable; nothing when no such
  // cell exists. Scratch space is a window around `from`, reused between calls.
  std::optional<Cell> find(const PlanningGrid& grid, Cell from, double radius_cells, UnknownPolicy policy);

 private:
  std::vector<uint32_t> seen_;  // stamp per window cell
  std::vector<Cell> queue_;
  uint32_t stamp_ = 0;
};

}  // namespace slam::planner
