// StartEscape: a bounded breadth-first search in a window around the robot's cell.
#include "planner/core/start_escape.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace slam::planner {

namespace {

bool wall(const PlanningGrid& grid, Cell c) {
  return (grid.at(c) & kCellStateMask) == kCellOccupied;
}

}  // namespace

std::optional<Cell> StartEscape::find(const PlanningGrid& grid, Cell from, double radius_cells,
                                      UnknownPolicy policy) {
  if (grid.empty() || !grid.contains(from)) return std::nullopt;
  if (!grid.impassable(from, policy)) return from;
  if (!std::isfinite(radius_cells) || radius_cells < 1.0) return std::nullopt;
  const auto r = static_cast<int32_t>(std::min(std::ceil(radius_cells), 1024.0));
  const int32_t side = 2 * r + 1;
  const auto window = static_cast<size_t>(side) * static_cast<size_t>(side);
  if (seen_.size() < window) seen_.assign(window, 0);
  if (stamp_ == std::numeric_limits<uint32_t>::max()) {
    std::fill(seen_.begin(), seen_.end(), 0);
    stamp_ = 0;
  }
  const uint32_t stamp = ++stamp_;
  const double r2 = radius_cells * radius_cells;
  const auto slot = [&](Cell c) {
    return static_cast<size_t>(c.y - from.y + r) * static_cast<size_t>(side) +
           static_cast<size_t>(c.x - from.x + r);
  };
  queue_.clear();
  queue_.push_back(from);
  seen_[slot(from)] = stamp;
  std::optional<Cell> best;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (size_t head = 0; head < queue_.size(); ++head) {
    const Cell c = queue_[head];
    for (int32_t dy = -1; dy <= 1; ++dy) {
      for (int32_t dx = -1; dx <= 1; ++dx) {
        if (dx == 0 && dy == 0) continue;
        const Cell n{c.x + dx, c.y + dy};
        const double ex = n.x - from.x;
        const double ey = n.y - from.y;
        const double d2 = ex * ex + ey * ey;
        if (d2 > r2 || !grid.contains(n) || seen_[slot(n)] == stamp) continue;
        if (wall(grid, n)) continue;
        // A diagonal step squeezing between two wall cells would pass through the wall.
        if (dx != 0 && dy != 0 && wall(grid, Cell{c.x + dx, c.y}) && wall(grid, Cell{c.x, c.y + dy}))
          continue;
        seen_[slot(n)] = stamp;
        if (!grid.impassable(n, policy)) {
          // Passable cells end the walk: the escape leg leads to the nearest one, not through it.
          if (d2 < best_d2) {
            best_d2 = d2;
            best = n;
          }
          continue;
        }
        queue_.push_back(n);
      }
    }
  }
  return best;
}

}  // namespace slam::planner
