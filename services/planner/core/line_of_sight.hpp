#pragma once
// Supercover segment walks: every grid cell a segment touches, including both side cells where it
// passes exactly through a corner. Planners use this instead of sampling along segments, which
// lets paths clip the corners of occupied cells (OMPL's motion validator samples that way).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "planner/core/planning_grid.hpp"

namespace slam::planner {

// Walks the cells touched by the segment a -> b, both in grid units (see PlanningGrid::to_grid),
// in order. visit(Cell, double t) gets each cell and the segment parameter in [0, 1] where the walk
// enters it; returning false stops the walk. Returns true when the walk reached b's cell.
template <class Visit>
bool walk_segment(Vec2 a, Vec2 b, Visit&& visit) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  constexpr double kTie = 1e-9;
  int32_t x = static_cast<int32_t>(std::floor(a.x));
  int32_t y = static_cast<int32_t>(std::floor(a.y));
  const int32_t xe = static_cast<int32_t>(std::floor(b.x));
  const int32_t ye = static_cast<int32_t>(std::floor(b.y));
  const double dx = b.x - a.x;
  const double dy = b.y - a.y;
  const int32_t sx = dx > 0 ? 1 : (dx < 0 ? -1 : 0);
  const int32_t sy = dy > 0 ? 1 : (dy < 0 ? -1 : 0);
  const double tdx = sx != 0 ? 1.0 / std::abs(dx) : kInf;
  const double tdy = sy != 0 ? 1.0 / std::abs(dy) : kInf;
  double tmx = sx > 0 ? (x + 1 - a.x) * tdx : (sx < 0 ? (a.x - x) * tdx : kInf);
  double tmy = sy > 0 ? (y + 1 - a.y) * tdy : (sy < 0 ? (a.y - y) * tdy : kInf);
  if (!visit(Cell{x, y}, 0.0)) return false;
  // Each step moves one cell closer in x or y, so this bounds the walk even with rounding.
  int64_t steps = std::abs(int64_t{xe} - x) + std::abs(int64_t{ye} - y);
  while (steps > 0 && (x != xe || y != ye)) {
    double t = 0.0;
    if (tmx < tmy - kTie) {
      t = tmx;
      x += sx;
      tmx += tdx;
      --steps;
    } else if (tmy < tmx - kTie) {
      t = tmy;
      y += sy;
      tmy += tdy;
      --steps;
    } else {
      t = tmx;
      if (!visit(Cell{x + sx, y}, t) || !visit(Cell{x, y + sy}, t)) return false;
      x += sx;
      y += sy;
      tmx += tdx;
      tmy += tdy;
      steps -= 2;
    }
    if (!visit(Cell{x, y}, std::min(t, 1.0))) return false;
  }
  return x == xe && y == ye;
}

// True when every cell the segment touches is inside the grid and passable under `policy`.
bool segment_clear(const PlanningGrid& grid, Vec2 a, Vec2 b, UnknownPolicy policy);

// Like segment_clear, but impassable cells at the start of the segment (inflated or unexplored; a
// wall only as the very first cell) are passed over until the first passable one: a leg that begins
// where a robot stands in an inflated or unexplored cell (an escape leg, see start_escape.hpp) is
// judged by where it leads, not by where the robot is.
bool segment_clear_leaving(const PlanningGrid& grid, Vec2 a, Vec2 b, UnknownPolicy policy);

// The segment parameter in [0, 1] where it first enters a cell that is impassable or outside the
// grid; 1.0 or more (infinity) when the whole segment is clear.
double first_blocked_fraction(const PlanningGrid& grid, Vec2 a, Vec2 b, UnknownPolicy policy);

}  // namespace slam::planner
