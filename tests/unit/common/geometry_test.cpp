// Points, SE(2) poses, cell boxes and grid geometry shared by every service.
#include "common/core/geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace slam {
namespace {

constexpr double kPi = std::numbers::pi;

void expect_near(Vec2 got, Vec2 want) {
  EXPECT_NEAR(got.x, want.x, 1e-12);
  EXPECT_NEAR(got.y, want.y, 1e-12);
}

void expect_near(const Pose& got, const Pose& want) {
  EXPECT_NEAR(got.x, want.x, 1e-12);
  EXPECT_NEAR(got.y, want.y, 1e-12);
  EXPECT_NEAR(wrap_angle(got.theta - want.theta), 0.0, 1e-12);
}

TEST(Vec2, ArithmeticDotCrossAndLengths) {
  const Vec2 a{3.0, 4.0}, b{1.0, -2.0};
  EXPECT_EQ(a + b, (Vec2{4.0, 2.0}));
  EXPECT_EQ(a - b, (Vec2{2.0, 6.0}));
  EXPECT_EQ(a * 2.0, (Vec2{6.0, 8.0}));
  EXPECT_DOUBLE_EQ(dot(a, b), -5.0);
  EXPECT_DOUBLE_EQ(cross(Vec2{1.0, 0.0}, Vec2{0.0, 1.0}), 1.0);  // counter-clockwise is positive
  EXPECT_DOUBLE_EQ(cross(a, b), -10.0);
  EXPECT_DOUBLE_EQ(norm(a), 5.0);
  EXPECT_DOUBLE_EQ(distance(a, b), std::hypot(2.0, 6.0));
}

TEST(WrapAngle, FoldsIntoHalfOpenRangeAboveMinusPi) {
  EXPECT_DOUBLE_EQ(wrap_angle(0.5), 0.5);
  EXPECT_NEAR(wrap_angle(2.0 * kPi + 0.5), 0.5, 1e-12);
  EXPECT_NEAR(wrap_angle(-2.0 * kPi - 0.5), -0.5, 1e-12);
  EXPECT_DOUBLE_EQ(wrap_angle(kPi), kPi);
  EXPECT_DOUBLE_EQ(wrap_angle(-kPi), kPi);
}

TEST(Pose, TransformRotatesThenTranslates) {
  const Pose p{1.0, 2.0, kPi / 2.0};
  expect_near(p.transform({1.0, 0.0}), {1.0, 3.0});
  expect_near(p.transform({0.0, 1.0}), {0.0, 2.0});
  expect_near(p.transform({0.0, 0.0}), p.position());
}

TEST(Pose, ComposeChainsFramesLikeTransformingTwice) {
  const Pose map_from_odom{0.5, -1.0, 0.3};
  const Pose odom_from_robot{2.0, 1.0, -1.2};
  const Pose map_from_robot = map_from_odom.compose(odom_from_robot);
  const Vec2 in_robot{0.7, -0.4};
  expect_near(map_from_robot.transform(in_robot),
              map_from_odom.transform(odom_from_robot.transform(in_robot)));
  EXPECT_NEAR(map_from_robot.theta, 0.3 - 1.2, 1e-12);
}

TEST(Pose, ComposeWrapsTheHeading) {
  const Pose a{0.0, 0.0, 3.0};
  EXPECT_NEAR(a.compose(Pose{0.0, 0.0, 3.0}).theta, 6.0 - 2.0 * kPi, 1e-12);
}

TEST(Pose, InverseUndoesThePoseOnEitherSide) {
  const Pose p{-3.0, 4.5, 2.5};
  expect_near(p.compose(p.inverse()), Pose{});
  expect_near(p.inverse().compose(p), Pose{});
  const Vec2 q{1.25, -7.0};
  expect_near(p.inverse().transform(p.transform(q)), q);
}

TEST(Pose, CorrectionBetweenTwoEstimatesMapsOneOntoTheOther) {
  // map<-odom = map<-robot ∘ (odom<-robot)^-1: the correction a SLAM core publishes.
  const Pose odom_from_robot{4.0, 1.0, 0.2};
  const Pose map_from_robot{3.5, 1.4, 0.25};
  const Pose map_from_odom = map_from_robot.compose(odom_from_robot.inverse());
  expect_near(map_from_odom.compose(odom_from_robot), map_from_robot);
}

TEST(CellBox, UniteGrowsToTheBoundingBoxAndIgnoresEmptyBoxes) {
  CellBox box;
  EXPECT_TRUE(box.empty());
  EXPECT_EQ(box.cells(), 0u);
  box.unite({2, 3, 2, 1});
  EXPECT_EQ(box, (CellBox{2, 3, 2, 1}));
  box.unite({-1, 5, 1, 2});  // negative cells: a box before the grid grows to hold it
  EXPECT_EQ(box, (CellBox{-1, 3, 5, 4}));
  box.unite({10, 10, 0, 4});
  EXPECT_EQ(box, (CellBox{-1, 3, 5, 4}));
  EXPECT_EQ(box.cells(), 20u);
}

TEST(GridGeometry, CellAtMapsPointsToCellsAndRejectsOutsideOrNonFinite) {
  const GridGeometry g{{-1.0, -2.0}, 0.5, 4, 3};
  EXPECT_EQ(g.cell_at({-1.0, -2.0}), (Cell{0, 0}));
  EXPECT_EQ(g.cell_at({0.2, -0.6}), (Cell{2, 2}));
  EXPECT_EQ(g.cell_at({0.99, -0.51}), (Cell{3, 2}));
  EXPECT_FALSE(g.cell_at({1.0, -1.0}));    // x = origin + width * resolution is outside
  EXPECT_FALSE(g.cell_at({-1.01, -1.0}));  // just left of the grid
  EXPECT_FALSE(g.cell_at({0.0, -0.5}));    // y at the upper end
  EXPECT_FALSE(g.cell_at({std::nan(""), 0.0}));
  EXPECT_FALSE(g.cell_at({0.0, INFINITY}));
  EXPECT_FALSE(GridGeometry{}.cell_at({0.0, 0.0}));  // no cells at all
}

TEST(GridGeometry, ClampedCellAtMovesOutsidePointsToTheBorder) {
  const GridGeometry g{{0.0, 0.0}, 1.0, 5, 4};
  EXPECT_EQ(g.clamped_cell_at({2.5, 1.5}), (Cell{2, 1}));
  EXPECT_EQ(g.clamped_cell_at({-3.0, 9.0}), (Cell{0, 3}));
  EXPECT_EQ(g.clamped_cell_at({7.0, -0.1}), (Cell{4, 0}));
}

TEST(GridGeometry, CentresCornersAndContinuousCoordinatesAgree) {
  const GridGeometry g{{-1.0, -2.0}, 0.5, 4, 3};
  expect_near(g.centre({1, 2}), {-0.25, -0.75});
  expect_near(g.corner({1, 2}), {-0.5, -1.0});
  expect_near(g.corner({g.width, g.height}), {1.0, -0.5});
  expect_near(g.to_grid({0.0, -1.0}), {2.0, 2.0});
  for (int32_t y = 0; y < g.height; ++y)
    for (int32_t x = 0; x < g.width; ++x) EXPECT_EQ(g.cell_at(g.centre({x, y})), (Cell{x, y}));
}

TEST(GridGeometry, IndexIsRowMajorAndCellOfInvertsIt) {
  const GridGeometry g{{0.0, 0.0}, 1.0, 4, 3};
  EXPECT_EQ(g.cells(), 12u);
  EXPECT_EQ(g.index({3, 0}), 3u);
  EXPECT_EQ(g.index({0, 1}), 4u);
  for (size_t i = 0; i < g.cells(); ++i) EXPECT_EQ(g.index(g.cell_of(i)), i);
  EXPECT_TRUE(g.contains({3, 2}));
  EXPECT_FALSE(g.contains({4, 2}));
  EXPECT_FALSE(g.contains({0, -1}));
}

}  // namespace
TEST(PositionSigma, IsTheLargerSpreadOfXAndY) {
  EXPECT_DOUBLE_EQ(position_sigma({0.0004, 0.001, 0.0, 0.0009, 0.0, 1.0}), 0.03);  // heading ignored
  EXPECT_DOUBLE_EQ(position_sigma({0.0, 0.0, 0.0, 0.0, 0.0, 0.0}), 0.0);
  EXPECT_TRUE(std::isnan(position_sigma({-0.01, 0.0, 0.0, 0.0004, 0.0, 0.0})));
  EXPECT_TRUE(std::isnan(position_sigma({0.01, 0.0, 0.0, std::nan(""), 0.0, 0.0})));
}

}  // namespace slam
