#pragma once
// Test helper: a hidden world (ASCII art, see grid_builder.hpp) that robots uncover within a
// sensing radius, with line of sight; the map starts all unknown.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "grid_builder.hpp"
#include "planner/core/frontiers.hpp"
#include "planner/core/line_of_sight.hpp"

namespace slam::planner::test {

class HiddenWorld {
 public:
  explicit HiddenWorld(const std::vector<std::string>& art, int sensing_radius_cells = 5)
      : truth_(grid_from_art(art)),
        map_(uniform_grid(truth_.width(), truth_.height(), kCellUnknown)),
        radius_(sensing_radius_cells) {}

  // Reveals what a robot at p sees; returns the changed box.
  CellBox sense(Vec2 p) {
    const int r = radius_;
    const Cell c = *truth_.cell_at(p);
    const int32_t x0 = std::max(0, c.x - r);
    const int32_t y0 = std::max(0, c.y - r);
    const int32_t x1 = std::min(truth_.width() - 1, c.x + r);
    const int32_t y1 = std::min(truth_.height() - 1, c.y + r);
    CellBox box{x0, y0, x1 - x0 + 1, y1 - y0 + 1};
    for (int32_t y = y0; y <= y1; ++y) {
      for (int32_t x = x0; x <= x1; ++x) {
        const Cell q{x, y};
        uint8_t v = map_.at(q);
        bool seen = true;
        walk_segment(truth_.to_grid(p), truth_.to_grid(truth_.centre(q)), [&](Cell k, double) {
          if (k == q) return true;
          seen = seen && !truth_.blocked(k);
          return seen;
        });
        if (seen && std::hypot(q.x - c.x, q.y - c.y) <= r) v = truth_.at(q);
        map_.set(q, v);
      }
    }
    return box;
  }
  const PlanningGrid& map() const { return map_; }
  const PlanningGrid& truth() const { return truth_; }

 private:
  PlanningGrid truth_;
  PlanningGrid map_;
  int radius_;
};

}  // namespace slam::planner::test
