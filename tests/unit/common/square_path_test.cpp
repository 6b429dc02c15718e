// The calibration square's corners: shared by the planner (square goals) and the viewer (corner
// buttons), for any plain point type.
#include "common/core/square_path.hpp"

#include <gtest/gtest.h>

namespace slam {
namespace {

struct Vec2 {
  double x = 0.0, y = 0.0;
};

void expect_at(const Vec2& got, double x, double y) {
  EXPECT_DOUBLE_EQ(got.x, x);
  EXPECT_DOUBLE_EQ(got.y, y);
}

TEST(SquareCorners, CornerAnchorStartsAtTheTargetAndRunsAnticlockwise) {
  const auto c = square_corners(Vec2{1.0, 2.0}, 2.0, false);
  expect_at(c[0], 1.0, 2.0);
  expect_at(c[1], 3.0, 2.0);
  expect_at(c[2], 3.0, 4.0);
  expect_at(c[3], 1.0, 4.0);
}

TEST(SquareCorners, CentredAnchorSurroundsTheTarget) {
  const auto c = square_corners(Vec2{1.0, 2.0}, 2.0, true);
  expect_at(c[0], 0.0, 1.0);
  expect_at(c[1], 2.0, 1.0);
  expect_at(c[2], 2.0, 3.0);
  expect_at(c[3], 0.0, 3.0);
}

TEST(SquareCorners, WorksForAnyPlainPointType) {
  struct P {
    double x, y;
  };
  constexpr auto c = square_corners(P{0.0, 0.0}, 1.0, false);
  static_assert(c[2].x == 1.0 && c[2].y == 1.0);
}

}  // namespace
}  // namespace slam
