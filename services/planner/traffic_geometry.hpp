#pragma once
// Polyline distances shared by the traffic rules (traffic_rules.cpp, way_clearing.cpp).
#include <algorithm>
#include <limits>
#include <span>

#include "planner/plan_types.hpp"

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

}  // namespace slam::planner::traffic
