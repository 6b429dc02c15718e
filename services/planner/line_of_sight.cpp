// Segment tests on a PlanningGrid in map coordinates, built on walk_segment.
#include "planner/line_of_sight.hpp"

namespace slam::planner {

bool segment_clear(const PlanningGrid& grid, Vec2 a, Vec2 b, UnknownPolicy policy) {
  return first_blocked_fraction(grid, a, b, policy) > 1.0;
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
