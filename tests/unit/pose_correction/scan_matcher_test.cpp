// ScanMatcher: recovers known offsets and rotations on synthetic maps (exact and noisy sparse
// sensors), reports a corridor's and a ring's ambiguity in its covariance (flat directions) and a
// second peak as ambiguity, honours the cell classes, reuses its buffers correctly, and refuses what
// it cannot match (too few points, off the grid, free space), and breaks ties towards the prediction.
// DistinctMatch: what a closure needs.
#include "pose_correction/scan_matcher.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "synthetic_world.hpp"

namespace slam::correction {
namespace {

using testkit::ClassGrid;
using testkit::keyframe_points;
using testkit::SparseSensor;
using testkit::SyntheticWorld;

constexpr double kResolution = 0.05;
constexpr double kHalfCell = kResolution / 2.0;
constexpr double kHalfDegree = 0.5 * std::numbers::pi / 180.0;

double degrees(double d) {
  return d * std::numbers::pi / 180.0;
}

GridGeometry geometry_over(Vec2 lo, Vec2 hi) {
  return testkit::centred_geometry(lo, hi, kResolution);
}

// A 6 x 5 m room with an L-shaped inner wall.
SyntheticWorld l_room() {
  SyntheticWorld w;
  w.room({0.0, 0.0}, {6.0, 5.0});
  w.wall({2.0, 1.5}, {2.0, 3.5});
  w.wall({2.0, 3.5}, {3.5, 3.5});
  return w;
}

// Six rooms of 4 x 4 m joined by 1 m doorways.
SyntheticWorld several_rooms() {
  SyntheticWorld w = testkit::six_rooms();
  w.wall({5.0, 5.0}, {6.0, 5.0});  // a cupboard breaks the symmetry of the middle room
  return w;
}

struct Scene {
  ClassGrid grid;
  std::vector<Vec2> points;
  Pose truth;
  GridView view() const { return {grid.geometry, grid.classes}; }
};

Scene scene(const SyntheticWorld& world, Vec2 lo, Vec2 hi, const Pose& truth, double noise_m = 0.0,
            unsigned seed = 7) {
  std::mt19937 rng(seed);
  SparseSensor sensor;
  sensor.noise_m = noise_m;
  Scene s{ClassGrid::rasterise(world, geometry_over(lo, hi)), {}, truth};
  // Ten v1 messages of ten beams while the robot drives 0.5 m and turns a little.
  s.points = keyframe_points(world, sensor, truth, {0.05, 0.0, 0.02}, 10, rng);
  return s;
}

Pose offset(const Pose& p, double dx, double dy, double dtheta) {
  return {p.x + dx, p.y + dy, p.theta + dtheta};
}

void expect_near_pose(const Pose& got, const Pose& want) {
  EXPECT_NEAR(got.x, want.x, kHalfCell);
  EXPECT_NEAR(got.y, want.y, kHalfCell);
  EXPECT_NEAR(wrap_angle(got.theta - want.theta), 0.0, kHalfDegree);
}

struct Offset {
  double dx, dy, dtheta_deg;
};

class ScanMatcherOffsets : public ::testing::TestWithParam<Offset> {};

TEST_P(ScanMatcherOffsets, RecoversTheTruePoseInARoomWithAnLShapedWall) {
  const Offset o = GetParam();
  const Scene s = scene(l_room(), {-1.0, -1.0}, {7.0, 6.0}, {4.0, 1.2, 0.3});
  ASSERT_GE(s.points.size(), 80u);
  ScanMatcher matcher;
  const auto r = matcher.match(s.view(), s.points, offset(s.truth, o.dx, o.dy, degrees(o.dtheta_deg)), {});
  ASSERT_TRUE(r) << r.message();
  expect_near_pose(r->pose, s.truth);
  EXPECT_GT(r->score, 0.9);
  EXPECT_EQ(r->points_used, static_cast<int>(s.points.size()));
}

TEST_P(ScanMatcherOffsets, RecoversTheTruePoseAmongSeveralRooms) {
  const Offset o = GetParam();
  const Scene s = scene(several_rooms(), {-1.0, -1.0}, {13.0, 9.0}, {5.5, 2.0, -1.0});
  ScanMatcher matcher;
  const auto r = matcher.match(s.view(), s.points, offset(s.truth, o.dx, o.dy, degrees(o.dtheta_deg)), {});
  ASSERT_TRUE(r) << r.message();
  expect_near_pose(r->pose, s.truth);
}

TEST_P(ScanMatcherOffsets, RecoversTheTruePoseFromANoisySparseSensor) {
  const Offset o = GetParam();
  const Scene s = scene(l_room(), {-1.0, -1.0}, {7.0, 6.0}, {1.0, 4.0, -0.4}, 0.01, 11);
  ScanMatcher matcher;
  const auto r = matcher.match(s.view(), s.points, offset(s.truth, o.dx, o.dy, degrees(o.dtheta_deg)), {});
  ASSERT_TRUE(r) << r.message();
  expect_near_pose(r->pose, s.truth);
  EXPECT_GT(r->score, 0.7);
}

INSTANTIATE_TEST_SUITE_P(KnownOffsets, ScanMatcherOffsets,
                         ::testing::Values(Offset{0.1, -0.08, 3.0}, Offset{-0.12, 0.05, -4.0},
                                           Offset{0.07, 0.11, 1.5}, Offset{0.0, 0.0, 0.0},
                                           Offset{-0.03, -0.13, 0.0}, Offset{0.0, 0.0, -4.5}));

TEST(ScanMatcher, CovarianceNearTheFloorWhenEveryDirectionIsConstrained) {
  const Scene s = scene(l_room(), {-1.0, -1.0}, {7.0, 6.0}, {4.0, 1.2, 0.3});
  ScanMatcher matcher;
  const auto r = matcher.match(s.view(), s.points, offset(s.truth, 0.05, 0.05, 0.02), {});
  ASSERT_TRUE(r) << r.message();
  EXPECT_LT(r->covariance(0, 0), (1.5 * kResolution) * (1.5 * kResolution));
  EXPECT_LT(r->covariance(1, 1), (1.5 * kResolution) * (1.5 * kResolution));
  EXPECT_LT(r->covariance(2, 2), degrees(1.5) * degrees(1.5));
  // The floor: never more certain than half a cell and half a degree.
  EXPECT_GE(r->covariance(0, 0), kHalfCell * kHalfCell);
  EXPECT_GE(r->covariance(2, 2), kHalfDegree * kHalfDegree * 0.999);
}

// A straight corridor 1.5 m wide and 40 m long, the robot in its middle with a sensor that never
// sees its ends.
struct CorridorScene {
  ClassGrid grid;
  std::vector<Vec2> points;
  Pose truth{0.0, 0.75, 0.0};
};

CorridorScene corridor_scene() {
  SyntheticWorld corridor;
  corridor.wall({-20.0, 0.0}, {20.0, 0.0});
  corridor.wall({-20.0, 1.5}, {20.0, 1.5});
  std::mt19937 rng(3);
  SparseSensor sensor;
  sensor.beams = 16;
  sensor.max_range_m = 3.0;
  CorridorScene s{ClassGrid::rasterise(corridor, geometry_over({-21.0, -1.0}, {21.0, 2.5})), {}};
  s.points = keyframe_points(corridor, sensor, s.truth, {0.05, 0.0, 0.0}, 10, rng);
  return s;
}

TEST(ScanMatcher, CorridorCovarianceIsLargeAlongAndSmallAcross) {
  const auto [grid, points, truth] = corridor_scene();
  ScanMatcher matcher;
  const auto r = matcher.match({grid.geometry, grid.classes}, points, offset(truth, 0.05, 0.08, 0.0), {});
  ASSERT_TRUE(r) << r.message();
  EXPECT_NEAR(r->pose.y, truth.y, kHalfCell);
  EXPECT_NEAR(wrap_angle(r->pose.theta - truth.theta), 0.0, kHalfDegree);
  EXPECT_GT(r->covariance(0, 0), 10.0 * r->covariance(1, 1));
  // Along the corridor the whole +-0.15 m window scores alike: the map does not bound x at all.
  EXPECT_EQ(r->flat_directions, 1);
  // Reported as spread uniformly over the window (+-0.15 m rounded out to whole cells, plus the
  // floor): tracking takes the best candidate along it only weakly.
  EXPECT_GT(r->covariance(0, 0), 0.15 * 0.15 / 3.0);
  EXPECT_LT(r->covariance(0, 0), 0.2 * 0.2 / 3.0 + 0.001);
  EXPECT_LT(r->covariance(1, 1), (1.5 * kResolution) * (1.5 * kResolution));
}

TEST(ScanMatcher, AlongAFlatCorridorTheMatchKeepsThePredictedPosition) {
  const auto [grid, points, truth] = corridor_scene();
  ScanMatcher matcher;
  // Every whole-cell shift along the corridor scores exactly alike: the tie goes to the prediction,
  // not to the window's corner, which would push every keyframe in a corridor the same way.
  for (const double along : {-0.1, 0.0, 0.1}) {
    const Pose predicted = offset(truth, along, 0.05, 0.0);
    const auto r = matcher.match({grid.geometry, grid.classes}, points, predicted, {});
    ASSERT_TRUE(r) << r.message();
    EXPECT_NEAR(r->pose.x, predicted.x, kHalfCell);
    EXPECT_NEAR(r->pose.y, truth.y, kHalfCell);
  }
}

// A ring corridor 1 m wide around (0, 0), radii 1.5 and 2.5 m, as the built-in track world.
SyntheticWorld ring() {
  SyntheticWorld w;
  constexpr int kSides = 64;
  for (double radius : {1.5, 2.5}) {
    for (int i = 0; i < kSides; ++i) {
      const double a0 = 2.0 * std::numbers::pi * i / kSides, a1 = 2.0 * std::numbers::pi * (i + 1) / kSides;
      w.wall({radius * std::cos(a0), radius * std::sin(a0)}, {radius * std::cos(a1), radius * std::sin(a1)});
    }
  }
  return w;
}

Scene ring_scene() {
  // The robot drives along the ring (heading +y at (2, 0)), seeing both walls.
  return scene(ring(), {-3.0, -3.0}, {3.0, 3.0}, {2.0, 0.0, std::numbers::pi / 2});
}

TEST(ScanMatcher, RingCovarianceIsUnboundedAlongTheRingAndTightAcrossIt) {
  const Scene s = ring_scene();
  ScanMatcher matcher;
  const auto r = matcher.match(s.view(), s.points, offset(s.truth, 0.03, 0.05, degrees(1.0)), {});
  ASSERT_TRUE(r) << r.message();
  // Across the ring (radially, x here) the walls pin the robot.
  EXPECT_NEAR(r->pose.x, s.truth.x, kHalfCell);
  EXPECT_LT(r->covariance(0, 0), (1.5 * kResolution) * (1.5 * kResolution));
  // Along it (y, with the heading turning with it: a rotation about the ring's centre) they do not.
  EXPECT_EQ(r->flat_directions, 1);
  EXPECT_GT(r->covariance(1, 1), 0.005);
  const double along_heading = r->covariance(1, 2) / std::sqrt(r->covariance(1, 1) * r->covariance(2, 2));
  EXPECT_GT(along_heading, 0.9) << "moving along the ring turns the robot with it";
}

TEST(ScanMatcher, RingClosureWindowIsAmbiguousAndNotDistinct) {
  const Scene s = ring_scene();
  ScanMatcher matcher;
  const auto r = matcher.match(s.view(), s.points, offset(s.truth, 0.1, -0.3, degrees(5.0)), {1.0, 0.3});
  ASSERT_TRUE(r) << r.message();
  RecordProperty("ambiguity_percent", static_cast<int>(r->ambiguity * 100));
  EXPECT_GT(r->ambiguity, 0.95);  // the ring's other stretches score as well as the best
  EXPECT_FALSE(DistinctMatch{}.accepts(*r));
}

TEST(ScanMatcher, TwoEqualPeaksAreAmbiguousAndNotDistinct) {
  // A corridor with a short crossbar every 0.6 m: shifted by one period it looks the same.
  SyntheticWorld periodic;
  periodic.wall({-10.0, 0.0}, {10.0, 0.0});
  periodic.wall({-10.0, 2.0}, {10.0, 2.0});
  for (int k = -16; k <= 16; ++k) periodic.wall({0.6 * k, 0.0}, {0.6 * k, 0.4});
  std::mt19937 rng(5);
  SparseSensor sensor;
  sensor.beams = 16;
  sensor.max_range_m = 3.0;
  const Pose truth{0.3, 1.0, 0.0};
  const auto points = keyframe_points(periodic, sensor, truth, {0.02, 0.0, 0.0}, 10, rng);
  const ClassGrid grid = ClassGrid::rasterise(periodic, geometry_over({-11.0, -1.0}, {11.0, 3.0}));
  ScanMatcher matcher;
  const auto r =
      matcher.match({grid.geometry, grid.classes}, points, offset(truth, 0.05, 0.0, 0.0), {1.0, 0.3});
  ASSERT_TRUE(r) << r.message();
  EXPECT_GT(r->ambiguity, 0.9);
  EXPECT_FALSE(DistinctMatch{}.accepts(*r));
}

TEST(ScanMatcher, DistinctRoomClosureWindowIsAccepted) {
  const Scene s = scene(l_room(), {-1.0, -1.0}, {7.0, 6.0}, {4.0, 1.2, 0.3});
  ScanMatcher matcher;
  const auto r = matcher.match(s.view(), s.points, offset(s.truth, 0.4, -0.3, degrees(8.0)), {1.0, 0.3});
  ASSERT_TRUE(r) << r.message();
  expect_near_pose(r->pose, s.truth);
  RecordProperty("ambiguity_percent", static_cast<int>(r->ambiguity * 100));
  EXPECT_EQ(r->flat_directions, 0);
  EXPECT_LT(r->ambiguity, 0.8);
  EXPECT_TRUE(DistinctMatch{}.accepts(*r));
}

TEST(ScanMatcher, ABestCandidateOnTheWindowsEdgeIsNotDistinct) {
  // The true pose lies 6 cm beyond a 0.3 m window: the best candidate the search can reach sits on
  // the window's edge, where the response is still rising. Its spread is sharp (2.5 cm) and its
  // ambiguity low (0.65), so only the edge tells it is not a peak: a closure must not take it. The
  // same keyframe with a window that holds the true pose is distinct.
  const Scene s = scene(l_room(), {-1.0, -1.0}, {7.0, 6.0}, {4.0, 1.2, 0.3});
  ScanMatcher matcher;
  const Pose predicted = offset(s.truth, 0.36, 0.0, 0.0);
  const auto cut = matcher.match(s.view(), s.points, predicted, {0.3, 0.1});
  ASSERT_TRUE(cut) << cut.message();
  EXPECT_TRUE(cut->at_window_edge);
  EXPECT_FALSE(DistinctMatch{}.accepts(*cut));
  const auto whole = matcher.match(s.view(), s.points, predicted, {1.0, 0.1});
  ASSERT_TRUE(whole) << whole.message();
  expect_near_pose(whole->pose, s.truth);
  EXPECT_FALSE(whole->at_window_edge);
  EXPECT_TRUE(DistinctMatch{}.accepts(*whole));
}

TEST(ScanMatcher, ObstructedCellsCountAsOccupied) {
  Scene s = scene(l_room(), {-1.0, -1.0}, {7.0, 6.0}, {4.0, 1.2, 0.3});
  for (uint8_t& c : s.grid.classes)
    if (c == kCellOccupied) c = kCellFree | kCellObstructed;
  ScanMatcher matcher;
  const auto r = matcher.match(s.view(), s.points, offset(s.truth, 0.1, -0.08, degrees(3.0)), {});
  ASSERT_TRUE(r) << r.message();
  expect_near_pose(r->pose, s.truth);
}

TEST(ScanMatcher, InflatedCellsDoNotCountAsOccupied) {
  Scene s = scene(l_room(), {-1.0, -1.0}, {7.0, 6.0}, {4.0, 1.2, 0.3});
  for (uint8_t& c : s.grid.classes)
    if (c == kCellOccupied) c = kCellFree | kCellInflated;
  ScanMatcher matcher;
  const auto r = matcher.match(s.view(), s.points, s.truth, {});
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("score"), std::string::npos) << r.message();
}

TEST(ScanMatcher, ReusedMatcherGivesTheSameResultAsAFreshOne) {
  const Scene room = scene(l_room(), {-1.0, -1.0}, {7.0, 6.0}, {4.0, 1.2, 0.3});
  const Scene rooms = scene(several_rooms(), {-1.0, -1.0}, {13.0, 9.0}, {5.5, 2.0, -1.0});
  const Pose predicted = offset(room.truth, 0.1, -0.08, degrees(3.0));
  ScanMatcher reused;
  ASSERT_TRUE(reused.match(rooms.view(), rooms.points, rooms.truth, {0.5, 0.2}));
  const auto again = reused.match(room.view(), room.points, predicted, {});
  const auto fresh = ScanMatcher{}.match(room.view(), room.points, predicted, {});
  ASSERT_TRUE(again && fresh);
  EXPECT_EQ(again->pose, fresh->pose);
  EXPECT_EQ(again->covariance, fresh->covariance);
  EXPECT_EQ(again->score, fresh->score);
}

TEST(ScanMatcher, TooFewPointsIsAnError) {
  const Scene s = scene(l_room(), {-1.0, -1.0}, {7.0, 6.0}, {4.0, 1.2, 0.3});
  const std::vector<Vec2> few(s.points.begin(), s.points.begin() + 11);
  ScanMatcher matcher;  // min_points 12
  const auto r = matcher.match(s.view(), few, s.truth, {});
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("points"), std::string::npos) << r.message();
}

TEST(ScanMatcher, WindowOffTheGridIsAnError) {
  const Scene s = scene(l_room(), {-1.0, -1.0}, {7.0, 6.0}, {4.0, 1.2, 0.3});
  ScanMatcher matcher;
  const auto r = matcher.match(s.view(), s.points, {100.0, 100.0, 0.0}, {});
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("off the grid"), std::string::npos) << r.message();
}

TEST(ScanMatcher, EmptyGridViewIsAnError) {
  const Scene s = scene(l_room(), {-1.0, -1.0}, {7.0, 6.0}, {4.0, 1.2, 0.3});
  ScanMatcher matcher;
  const auto r = matcher.match(GridView{}, s.points, s.truth, {});
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("empty"), std::string::npos) << r.message();
}

TEST(ScanMatcher, NonFinitePredictionIsAnError) {
  const Scene s = scene(l_room(), {-1.0, -1.0}, {7.0, 6.0}, {4.0, 1.2, 0.3});
  ScanMatcher matcher;
  EXPECT_FALSE(matcher.match(s.view(), s.points, {std::nan(""), 1.0, 0.0}, {}));
}

TEST(ScanMatcher, MatchInFreeSpaceIsALowScoreError) {
  // Points seen in the small room, predicted in the middle of a large empty hall.
  const Scene s = scene(l_room(), {-1.0, -1.0}, {7.0, 6.0}, {4.0, 1.2, 0.3});
  SyntheticWorld hall;
  hall.room({0.0, 0.0}, {20.0, 20.0});
  const ClassGrid grid = ClassGrid::rasterise(hall, geometry_over({-1.0, -1.0}, {21.0, 21.0}));
  ScanMatcher matcher;
  const auto r = matcher.match({grid.geometry, grid.classes}, s.points, {10.0, 10.0, 0.0}, {});
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("score"), std::string::npos) << r.message();
}

}  // namespace
}  // namespace slam::correction
