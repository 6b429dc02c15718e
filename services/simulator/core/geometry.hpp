#pragma once
// Plane geometry the simulator's hot loops share: segments, boxes, and the exact intersection and
// distance tests that ray casting and collision checks are built from (points and poses are the
// common ones).
#include <algorithm>
#include <cmath>

#include "common/core/geometry.hpp"

namespace slam::sim {

struct Segment {
  Vec2 a;
  Vec2 b;
};

// Axis-aligned rectangle [min, max].
struct Bounds {
  Vec2 min;
  Vec2 max;
  double width() const { return max.x - min.x; }
  double height() const { return max.y - min.y; }
  bool contains(Vec2 p) const { return p.x >= min.x && p.x <= max.x && p.y >= min.y && p.y <= max.y; }
};

// Distance along the unit-length ray (origin, dir) to segment s, or +inf when it misses.
// Collinear overlap counts as a miss: a beam grazing along a wall sees the walls it meets end-on.
inline double ray_segment(Vec2 origin, Vec2 dir, const Segment& s) {
  const Vec2 e = s.b - s.a;
  const double denom = cross(dir, e);
  if (denom == 0.0) return INFINITY;
  const Vec2 w = s.a - origin;
  const double t = cross(w, e) / denom;
  const double u = cross(w, dir) / denom;
  if (t < 0.0 || u < 0.0 || u > 1.0) return INFINITY;
  return t;
}

// Distance along the unit-length ray to the circle (centre, radius), or +inf; a ray starting
// inside the circle hits it at 0 (the beam is blocked at once).
inline double ray_circle(Vec2 origin, Vec2 dir, Vec2 centre, double radius) {
  const Vec2 m = origin - centre;
  const double c = dot(m, m) - radius * radius;
  if (c <= 0.0) return 0.0;
  const double b = dot(m, dir);
  if (b > 0.0) return INFINITY;
  const double disc = b * b - c;
  if (disc < 0.0) return INFINITY;
  return -b - std::sqrt(disc);
}

// Squared distance from p to the closest point of s (degenerate segments are points).
inline double distance_sq(Vec2 p, const Segment& s) {
  const Vec2 e = s.b - s.a;
  const double len_sq = dot(e, e);
  double t = len_sq > 0.0 ? dot(p - s.a, e) / len_sq : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const Vec2 d = p - (s.a + e * t);
  return dot(d, d);
}

// True when segments p and q share a point (touching counts).
inline bool segments_intersect(const Segment& p, const Segment& q) {
  const auto orient = [](Vec2 a, Vec2 b, Vec2 c) { return cross(b - a, c - a); };
  const auto on_box = [](Vec2 a, Vec2 b, Vec2 c) {
    return std::min(a.x, b.x) <= c.x && c.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= c.y &&
           c.y <= std::max(a.y, b.y);
  };
  const double d1 = orient(q.a, q.b, p.a);
  const double d2 = orient(q.a, q.b, p.b);
  const double d3 = orient(p.a, p.b, q.a);
  const double d4 = orient(p.a, p.b, q.b);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  return (d1 == 0 && on_box(q.a, q.b, p.a)) || (d2 == 0 && on_box(q.a, q.b, p.b)) ||
         (d3 == 0 && on_box(p.a, p.b, q.a)) || (d4 == 0 && on_box(p.a, p.b, q.b));
}

}  // namespace slam::sim
