#pragma once
// Turns a dense path (one point per grid cell, or an OMPL state list) into the few waypoints a
// robot drives: collinear points go first, then any point the robot can skip because the
// straight segment past it stays clear on the grid.
#include <vector>

#include "planner/core/plan_types.hpp"
#include "planner/core/planning_grid.hpp"

namespace slam::planner {

// Removes interior points lying on the straight line between their neighbours (and repeated
// points). The first and last points always stay.
std::vector<Vec2> drop_collinear(const std::vector<Vec2>& points);

// Greedy shortcut: from each kept point, jump to the farthest following point whose segment is
// clear (segment_clear under `policy`). The result is never longer than the input.
std::vector<Vec2> shortcut(const PlanningGrid& grid, const std::vector<Vec2>& points, UnknownPolicy policy);

// A* cells -> waypoints: cell centres with the exact start and goal at the ends, then
// drop_collinear and shortcut.
std::vector<Vec2> reduce_cell_path(const PlanningGrid& grid, const std::vector<Cell>& cells, Vec2 start,
                                   Vec2 goal, UnknownPolicy policy);

}  // namespace slam::planner
