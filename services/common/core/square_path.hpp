#pragma once
// The calibration square's corners: the one definition of where a square path runs. The planner
// drives them (GoalMode::Square) and the viewer's Drive tab sends robots to single corners, so
// both must agree. A template over the point type because each service has its own plain {x, y}.
#include <array>

namespace slam {

// The four corners in driving order (anticlockwise). Corner anchor (centred = false): `target` is
// the first corner and the square extends to +x, +y. Centred: `target` is the centre. A square
// path closes by driving back to the first corner.
template <class Point>
constexpr std::array<Point, 4> square_corners(Point target, double size, bool centred) {
  const Point c0 = centred ? Point{target.x - size / 2, target.y - size / 2} : target;
  return {c0, Point{c0.x + size, c0.y}, Point{c0.x + size, c0.y + size}, Point{c0.x, c0.y + size}};
}

}  // namespace slam
