#pragma once
// Polyline and wall distances shared by the traffic rules' passes and fleet_coordinator.cpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "planner/core/plan_types.hpp"
#include "planner/core/planning_grid.hpp"

namespace slam::planner::traffic {

constexpr double kYieldMarginM = 0.05;  // a place off a way keeps this much more than the bare reach

// Distance between segments ab and cd (0 when they cross).
inline double segment_gap(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const auto cross = [](Vec2 o, Vec2 p, Vec2 q) {
    return (p.x - o.x) * (q.y - o.y) - (p.y - o.y) * (q.x - o.x);
  };
  const double d1 = cross(a, b, c), d2 = cross(a, b, d), d3 = cross(c, d, a), d4 = cross(c, d, b);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return 0.0;
  return std::min({distance_to_segment(a, c, d), distance_to_segment(b, c, d), distance_to_segment(c, a, b),
                   distance_to_segment(d, a, b)});
}

// Distance from p to the polyline (a single point counts as a polyline).
inline double gap_to(std::span<const Vec2> line, Vec2 p) {
  if (line.size() == 1) return distance(line[0], p);
  double best = std::numeric_limits<double>::infinity();
  for (size_t k = 1; k < line.size(); ++k)
    best = std::min(best, distance_to_segment(p, line[k - 1], line[k]));
  return best;
}

// Closest approach of p to the first `length` metres of the polyline.
inline double gap_to_prefix(std::span<const Vec2> line, double length, Vec2 p) {
  double best = distance(line[0], p);
  double walked = 0.0;
  for (size_t k = 1; k < line.size() && walked < length; ++k) {
    const double seg = distance(line[k - 1], line[k]);
    Vec2 end = line[k];
    if (walked + seg > length && seg > 0.0)
      end = line[k - 1] + (line[k] - line[k - 1]) * ((length - walked) / seg);
    best = std::min(best, distance_to_segment(p, line[k - 1], end));
    walked += seg;
  }
  return best;
}

// How far along the polyline the point of it nearest to p lies.
inline double along(std::span<const Vec2> line, Vec2 p) {
  double best = std::numeric_limits<double>::infinity(), best_at = 0.0, walked = 0.0;
  for (size_t k = 1; k < line.size(); ++k) {
    const Vec2 d = line[k] - line[k - 1];
    const double len = norm(d);
    const double t = len > 0.0 ? std::clamp(dot(p - line[k - 1], d) / (len * len), 0.0, 1.0) : 0.0;
    const double gap = distance(p, line[k - 1] + d * t);
    if (gap < best) {
      best = gap;
      best_at = walked + t * len;
    }
    walked += len;
  }
  return best_at;
}

// Distance from p to the nearest occupied cell (its square, not its centre: the wall can lie
// anywhere in it), or `limit` when none is nearer.
inline double wall_gap(const PlanningGrid& grid, Vec2 p, double limit) {
  const Vec2 g = grid.to_grid(p);
  const auto reach = static_cast<int32_t>(std::ceil(limit / grid.resolution()));
  const auto cx = static_cast<int32_t>(std::floor(g.x)), cy = static_cast<int32_t>(std::floor(g.y));
  double best = limit;
  for (int32_t y = cy - reach; y <= cy + reach; ++y)
    for (int32_t x = cx - reach; x <= cx + reach; ++x) {
      const Cell c{x, y};
      if (!grid.contains(c) || (grid.at(c) & kCellStateMask) != kCellOccupied) continue;
      const double dx = std::max({static_cast<double>(x) - g.x, 0.0, g.x - static_cast<double>(x + 1)});
      const double dy = std::max({static_cast<double>(y) - g.y, 0.0, g.y - static_cast<double>(y + 1)});
      best = std::min(best, std::hypot(dx, dy) * grid.resolution());
    }
  return best;
}

// True when a body of `radius` driving straight from `from` to `to` keeps `radius` from every wall,
// or, standing nearer than that, gets no nearer to a wall anywhere on the way until it is `radius`
// clear (a robot pressed against a wall may only drive away from it). A step that a planner's cell
// test passes can still clip a wall's corner with the body: a robot sent so stops there for good.
inline bool keeps_off_walls(const PlanningGrid& grid, Vec2 from, Vec2 to, double radius) {
  if (grid.empty()) return true;
  // The least gap allowed from here on: the radius, or below it the largest gap reached so far.
  double least = std::min(radius, wall_gap(grid, from, radius)) - 1e-9;
  const double length = distance(from, to);
  const double step = 0.5 * grid.resolution();
  for (double s = step; s < length + step; s += step) {
    const Vec2 p = from + (to - from) * (std::min(s, length) / length);
    const double gap = wall_gap(grid, p, radius);
    if (gap < least) return false;
    least = std::min(radius, std::max(least, gap)) - 1e-9;
  }
  return true;
}

}  // namespace slam::planner::traffic
