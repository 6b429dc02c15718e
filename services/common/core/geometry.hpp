#pragma once
// Plane geometry every service shares: map-frame points, SE(2) poses, integer cells and boxes of
// cells, and the geometry of a regular grid (where cell (0, 0) lies, how large a cell is). One
// definition, so the mapper, planner, simulator and viewer agree on what "cell (i, j)" means.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <optional>

namespace slam {

// A point or a direction in the map frame (metres).
struct Vec2 {
  double x = 0.0;
  double y = 0.0;
  bool operator==(const Vec2&) const = default;
};

inline Vec2 operator+(Vec2 a, Vec2 b) {
  return {a.x + b.x, a.y + b.y};
}
inline Vec2 operator-(Vec2 a, Vec2 b) {
  return {a.x - b.x, a.y - b.y};
}
inline Vec2 operator*(Vec2 a, double s) {
  return {a.x * s, a.y * s};
}
inline double dot(Vec2 a, Vec2 b) {
  return a.x * b.x + a.y * b.y;
}
// z component of the 3-D cross product: positive when b lies counter-clockwise of a.
inline double cross(Vec2 a, Vec2 b) {
  return a.x * b.y - a.y * b.x;
}
inline double norm(Vec2 a) {
  return std::hypot(a.x, a.y);
}
inline double distance(Vec2 a, Vec2 b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}

// Angle folded into (-pi, pi].
inline double wrap_angle(double a) {
  a = std::remainder(a, 2.0 * std::numbers::pi);
  return a <= -std::numbers::pi ? a + 2.0 * std::numbers::pi : a;
}

// Radians as degrees, for people: logs and printed figures.
inline double to_degrees(double radians) {
  return radians * (180.0 / std::numbers::pi);
}

// The larger of the x and y standard deviations (m) of an (x, y, theta) covariance kept as its upper
// triangle (xx, xy, xt, yy, yt, tt), as PoseCorrection carries it: a corridor's length is what is
// least known. NaN when either variance is negative or not finite.
inline double position_sigma(const std::array<double, 6>& upper) {
  if (!(upper[0] >= 0.0) || !(upper[3] >= 0.0)) return std::nan("");
  return std::sqrt(std::max(upper[0], upper[3]));
}

// An SE(2) pose: position plus heading theta (radians, counter-clockwise from +x). Read as the
// transform from the pose's own frame into the frame it is expressed in (robot -> map).
struct Pose {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
  bool operator==(const Pose&) const = default;

  Vec2 position() const { return {x, y}; }
  // A point given in this pose's frame, expressed in the outer frame.
  Vec2 transform(Vec2 p) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * p.x - s * p.y, y + s * p.x + c * p.y};
  }
  // this ∘ inner: `inner` is expressed in this pose's frame (map<-odom ∘ odom<-robot = map<-robot).
  Pose compose(const Pose& inner) const {
    const Vec2 p = transform(inner.position());
    return {p.x, p.y, wrap_angle(theta + inner.theta)};
  }
  // The outer frame seen from this pose, so that compose(inverse()) is the identity.
  Pose inverse() const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {-c * x - s * y, s * x - c * y, wrap_angle(-theta)};
  }
};

inline bool is_finite(const Pose& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta);
}

// Integer cell coordinates in a grid; (0, 0) is the lowest-left cell, y grows with rows.
struct Cell {
  int32_t x = 0;
  int32_t y = 0;
  bool operator==(const Cell&) const = default;
};

// The cells [x0, x0 + width) x [y0, y0 + height). Signed so boxes can be expressed in a grid's
// coordinates before the grid grows to hold them (the mapper grows towards negative cells).
struct CellBox {
  int32_t x0 = 0;
  int32_t y0 = 0;
  int32_t width = 0;
  int32_t height = 0;
  bool operator==(const CellBox&) const = default;

  bool empty() const { return width <= 0 || height <= 0; }
  size_t cells() const { return empty() ? 0 : static_cast<size_t>(width) * static_cast<size_t>(height); }
  // Grows to the bounding box of both; an empty box adds nothing.
  void unite(const CellBox& o) {
    if (o.empty()) return;
    if (empty()) {
      *this = o;
      return;
    }
    const int32_t x1 = std::max(x0 + width, o.x0 + o.width), y1 = std::max(y0 + height, o.y0 + o.height);
    x0 = std::min(x0, o.x0);
    y0 = std::min(y0, o.y0);
    width = x1 - x0;
    height = y1 - y0;
  }
};

// A row-major grid of width x height square cells; cell (i, j) covers
// [origin.x + i * resolution, origin.x + (i + 1) * resolution) and likewise in y.
struct GridGeometry {
  Vec2 origin;              // map position of cell (0, 0)'s lower-left corner
  double resolution = 1.0;  // metres per cell side
  int32_t width = 0;        // cells
  int32_t height = 0;       // cells

  size_t cells() const {
    return static_cast<size_t>(std::max(width, 0)) * static_cast<size_t>(std::max(height, 0));
  }
  bool contains(Cell c) const { return c.x >= 0 && c.y >= 0 && c.x < width && c.y < height; }
  size_t index(Cell c) const {
    return static_cast<size_t>(c.y) * static_cast<size_t>(width) + static_cast<size_t>(c.x);
  }
  Cell cell_of(size_t index) const {
    return {static_cast<int32_t>(index % static_cast<size_t>(width)),
            static_cast<int32_t>(index / static_cast<size_t>(width))};
  }

  // Map point in cell units relative to the origin (unbounded, not rounded).
  Vec2 to_grid(Vec2 p) const { return {(p.x - origin.x) / resolution, (p.y - origin.y) / resolution}; }
  // The cell holding a map point; nothing when the point lies outside the grid or is not finite.
  std::optional<Cell> cell_at(Vec2 p) const {
    const Vec2 g = to_grid(p);
    const double fx = std::floor(g.x), fy = std::floor(g.y);
    if (!(fx >= 0.0 && fy >= 0.0 && fx < width && fy < height)) return std::nullopt;
    return Cell{static_cast<int32_t>(fx), static_cast<int32_t>(fy)};
  }
  // The cell holding a map point, with points outside the grid moved to its nearest border cell.
  Cell clamped_cell_at(Vec2 p) const {
    const Vec2 g = to_grid(p);
    return {std::clamp(static_cast<int32_t>(std::floor(g.x)), 0, width - 1),
            std::clamp(static_cast<int32_t>(std::floor(g.y)), 0, height - 1)};
  }
  // Lower-left corner of cell c (c may lie outside: corner({width, height}) is the upper-right end).
  Vec2 corner(Cell c) const { return {origin.x + c.x * resolution, origin.y + c.y * resolution}; }
  Vec2 centre(Cell c) const {
    return {origin.x + (c.x + 0.5) * resolution, origin.y + (c.y + 0.5) * resolution};
  }
};

}  // namespace slam
