// Path reduction: collinear removal and line-of-sight shortcutting.
#include "planner/core/path_reduction.hpp"

#include <cmath>

#include "planner/core/line_of_sight.hpp"

namespace slam::planner {

namespace {

// Relative tolerance for "on the line": cell centres are exact in binary for usual resolutions,
// OMPL states are not.
constexpr double kCollinearTolerance = 1e-9;

bool collinear(Vec2 a, Vec2 b, Vec2 c) {
  const double abx = b.x - a.x;
  const double aby = b.y - a.y;
  const double bcx = c.x - b.x;
  const double bcy = c.y - b.y;
  const double cross = abx * bcy - aby * bcx;
  const double dot = abx * bcx + aby * bcy;
  const double scale = std::hypot(abx, aby) * std::hypot(bcx, bcy);
  return dot > 0.0 && std::abs(cross) <= kCollinearTolerance * scale;
}

}  // namespace

std::vector<Vec2> drop_collinear(const std::vector<Vec2>& points) {
  std::vector<Vec2> out;
  out.reserve(points.size());
  for (const Vec2& p : points) {
    if (!out.empty() && out.back() == p) continue;
    while (out.size() >= 2 && collinear(out[out.size() - 2], out.back(), p)) out.pop_back();
    out.push_back(p);
  }
  return out;
}

std::vector<Vec2> shortcut(const PlanningGrid& grid, const std::vector<Vec2>& points, UnknownPolicy policy) {
  if (points.size() <= 2) return points;
  std::vector<Vec2> out;
  out.reserve(points.size());
  size_t anchor = 0;
  out.push_back(points[0]);
  while (anchor + 1 < points.size()) {
    // The next point is always reachable (it is the input path); reach further while clear.
    size_t next = anchor + 1;
    for (size_t j = anchor + 2; j < points.size(); ++j) {
      if (!segment_clear(grid, points[anchor], points[j], policy)) break;
      next = j;
    }
    out.push_back(points[next]);
    anchor = next;
  }
  return out;
}

std::vector<Vec2> reduce_cell_path(const PlanningGrid& grid, const std::vector<Cell>& cells, Vec2 start,
                                   Vec2 goal, UnknownPolicy policy) {
  std::vector<Vec2> points;
  points.reserve(cells.size() + 1);
  points.push_back(start);
  for (size_t i = 1; i + 1 < cells.size(); ++i) points.push_back(grid.centre(cells[i]));
  points.push_back(goal);
  return shortcut(grid, drop_collinear(points), policy);
}

}  // namespace slam::planner
