// Segment tests on a PlanningGrid in map coordinates, built on walk_segment.
#include "planner/core/line_of_sight.hpp"

namespace slam::planner {

bool segment_clear(const PlanningGrid& grid, Vec2 a, Vec2 b, UnknownPolicy policy) {
  return first_blocked_fraction(grid, a, b, policy) > 1.0;
}

bool segment_clear_leaving(const PlanningGrid& grid, Vec2 a, Vec2 b, UnknownPolicy policy) {
  if (grid.empty()) return false;
  bool first = true;
  bool left = false;  // reached the first passable cell
  bool clear = true;
  walk_segment(grid.to_grid(a), grid.to_grid(b), [&](Cell c, double) {
    if (!grid.contains(c)) {
      clear = false;
      return false;
    }
    const bool passable = !grid.impassable(c, policy);
    // Whatever the robot stands on, it may leave; on the way out it may not cross a wall.
    const bool wall = (grid.at(c) & kCellStateMask) == kCellOccupied;
    if (!passable && (left || (wall && !first))) {
      clear = false;
      return false;
    }
    first = false;
    left = left || passable;
    return true;
  });
  // A leg that never leaves impassable cells is not a way anywhere.
  return clear && left;
}

double first_blocked_fraction(const PlanningGrid& grid, Vec2 a, Vec2 b, UnknownPolicy policy) {
  if (grid.empty()) return 0.0;
  double hit = std::numeric_limits<double>::infinity();
  walk_segment(grid.to_grid(a), grid.to_grid(b), [&](Cell c, double t) {
    if (!grid.contains(c) || grid.impassable(c, policy)) {
      hit = t;
      return false;
    }
    return true;
  });
  return hit;
}

}  // namespace slam::planner
