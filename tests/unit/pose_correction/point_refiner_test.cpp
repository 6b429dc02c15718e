#include "pose_correction/point_refiner.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "pose_correction/gaussian_pose.hpp"

namespace slam::correction {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

struct Segment {
  Vec2 a, b;
};

// Points every `spacing` metres along the segments, `noise` metres off across them.
std::vector<Vec2> sample(const std::vector<Segment>& walls, double spacing, double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> across(0.0, noise);
  std::vector<Vec2> out;
  for (const Segment& w : walls) {
    const double length = distance(w.a, w.b);
    const Vec2 along = (w.b - w.a) * (1.0 / length);
    const Vec2 normal{-along.y, along.x};
    for (double t = 0.0; t <= length; t += spacing) out.push_back(w.a + along * t + normal * across(rng));
  }
  return out;
}

// A room's corner with a door jamb: walls along x and y, enough to pin x, y and heading.
std::vector<Segment> corner() {
  return {
      {{0.0, 0.0}, {3.0, 0.0}}, {{0.0, 0.0}, {0.0, 2.5}}, {{1.6, 2.0}, {3.0, 2.0}}, {{1.6, 2.0}, {1.6, 2.4}}};
}

// The keyframe's points in its own frame, as seen from `truth`.
std::vector<Vec2> seen_from(const Pose& truth, const std::vector<Vec2>& world) {
  std::vector<Vec2> local;
  for (const Vec2& p : world) local.push_back(truth.inverse().transform(p));
  return local;
}

TEST(PointRefiner, RecoversAnOffsetWithinACellAndHalfAHeadingStep) {
  PointRefiner refiner;
  // The reference: the map's points, dense (several keyframes over the same walls).
  const auto reference = sample(corner(), 0.03, 0.005, 1);
  refiner.set_reference(reference);
  const Pose truth{1.2, 0.9, 0.3};
  // The keyframe: sparse points on the same walls, from a different draw.
  const auto points = seen_from(truth, sample(corner(), 0.11, 0.005, 2));
  // Started where a grid search leaves it: half a cell off and less than half a heading step.
  const Pose start{truth.x + 0.025, truth.y - 0.02, truth.theta + 0.3 * kDegree};
  const auto refined = refiner.refine(points, start, diagonal(0.025, 0.025, 0.5 * kDegree));
  ASSERT_TRUE(refined.has_value());
  EXPECT_NEAR(refined->pose.x, truth.x, 0.003);
  EXPECT_NEAR(refined->pose.y, truth.y, 0.003);
  EXPECT_NEAR(refined->pose.theta, truth.theta, 0.1 * kDegree);
  EXPECT_GT(refined->inliers, static_cast<int>(points.size()) * 3 / 4);
}

TEST(PointRefiner, LeavesACorridorsLengthWhereTheSearchPutIt) {
  PointRefiner refiner;
  const std::vector<Segment> corridor{{{0.0, 0.0}, {8.0, 0.0}}, {{0.0, 1.2}, {8.0, 1.2}}};
  refiner.set_reference(sample(corridor, 0.03, 0.004, 3));
  const Pose truth{3.0, 0.6, 0.0};
  std::vector<Vec2> world;
  for (const Vec2& p : sample(corridor, 0.1, 0.004, 4))
    if (std::abs(p.x - truth.x) < 2.0) world.push_back(p);
  const auto points = seen_from(truth, world);
  // Off by 4 cm along the corridor (which nothing in it pins) and 2 cm across (which the walls do).
  const Pose start{truth.x + 0.04, truth.y + 0.02, truth.theta};
  const auto refined = refiner.refine(points, start, diagonal(0.05, 0.05, 1.0 * kDegree));
  ASSERT_TRUE(refined.has_value());
  EXPECT_NEAR(refined->pose.y, truth.y, 0.003);  // across: pulled onto the walls
  EXPECT_NEAR(refined->pose.x, start.x, 0.003);  // along: the prior holds it, 4 cm off
  EXPECT_NEAR(refined->pose.theta, truth.theta, 0.1 * kDegree);
}

TEST(PointRefiner, GivesNothingWithoutLinesToPullOnto) {
  PointRefiner refiner;
  const Pose truth{1.2, 0.9, 0.3};
  const auto points = seen_from(truth, sample(corner(), 0.11, 0.005, 2));
  const Eigen::Matrix3d prior = diagonal(0.025, 0.025, 0.01);
  // No reference at all.
  EXPECT_FALSE(refiner.refine(points, truth, prior).has_value());
  // A reference elsewhere: no keyframe point finds a line.
  std::vector<Vec2> elsewhere = sample(corner(), 0.03, 0.005, 1);
  for (Vec2& p : elsewhere) p = p + Vec2{20.0, 0.0};
  refiner.set_reference(elsewhere);
  EXPECT_FALSE(refiner.refine(points, truth, prior).has_value());
  // Scattered reference points (clutter, no walls): no line anywhere.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> anywhere(-0.5, 3.5);
  std::vector<Vec2> clutter;
  for (int i = 0; i < 3000; ++i) clutter.push_back({anywhere(rng), anywhere(rng)});
  refiner.set_reference(clutter);
  EXPECT_FALSE(refiner.refine(points, truth, prior).has_value());
}

TEST(PointRefiner, RefusesAMoveFartherThanTheSearchCouldHaveMissed) {
  PointRefiner refiner;
  // The map holds only the second of two parallel walls 20 cm apart; a keyframe on the first,
  // started 8 cm toward the second, would be pulled onto it: a move larger than a grid search
  // misses by, so a wrong association.
  const std::vector<Segment> walls{
      {{0.0, 0.0}, {3.0, 0.0}}, {{0.0, 0.2}, {3.0, 0.2}}, {{0.0, 0.0}, {0.0, 2.0}}};
  refiner.set_reference(sample({walls[1], walls[2]}, 0.03, 0.003, 6));
  const auto points = seen_from(Pose{}, sample({walls[0], walls[2]}, 0.1, 0.003, 7));
  const Pose start{0.0, 0.08, 0.0};
  EXPECT_FALSE(refiner.refine(points, start, diagonal(0.1, 0.1, 0.05)).has_value());
}

TEST(PointRefiner, RefusesATurnBeyondHalfTheSearchsHeadingStep) {
  // Started a degree off (more than half the search's step), the points would turn the pose back by
  // that much: the heading of the reference, not a cell's quantisation, so the search's result stands.
  PointRefiner refiner;
  refiner.set_reference(sample(corner(), 0.03, 0.005, 1));
  const Pose truth{1.2, 0.9, 0.3};
  const auto points = seen_from(truth, sample(corner(), 0.11, 0.005, 2));
  const Eigen::Matrix3d prior = diagonal(0.025, 0.025, 1.0 * kDegree);
  EXPECT_FALSE(refiner.refine(points, {truth.x, truth.y, truth.theta + 1.0 * kDegree}, prior).has_value());
  EXPECT_TRUE(refiner.refine(points, {truth.x, truth.y, truth.theta + 0.2 * kDegree}, prior).has_value());
}

TEST(PointRefiner, IgnoresNonFiniteReferencePointsAndIsReusable) {
  PointRefiner refiner;
  auto reference = sample(corner(), 0.03, 0.005, 1);
  reference.push_back({std::nan(""), 1.0});
  reference.push_back({1.0, std::numeric_limits<double>::infinity()});
  refiner.set_reference(reference);
  EXPECT_EQ(refiner.reference_size(), reference.size() - 2);
  const Pose truth{1.2, 0.9, 0.3};
  const auto points = seen_from(truth, sample(corner(), 0.11, 0.005, 2));
  const Pose start{truth.x - 0.02, truth.y + 0.01, truth.theta};
  const auto first = refiner.refine(points, start, diagonal(0.025, 0.025, 0.01));
  ASSERT_TRUE(first.has_value());
  // The same reference set again gives the same answer (the bins are rebuilt, not appended).
  refiner.set_reference(reference);
  const auto second = refiner.refine(points, start, diagonal(0.025, 0.025, 0.01));
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(first->pose, second->pose);
  EXPECT_NEAR(first->pose.x, truth.x, 0.003);
}

}  // namespace
}  // namespace slam::correction
