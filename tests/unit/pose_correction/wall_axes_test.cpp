#include "pose_correction/wall_axes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace slam::correction {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// Points along a room's corner as a sparse range sensor leaves them: two walls meeting at a right
// angle (3 m and 2 m seen), a short stretch of a third parallel to the first, and a little clutter,
// all turned by `rotation` and moved by `offset`; the points are `noise` metres off across.
std::vector<Vec2> corner_points(double rotation, Vec2 offset, double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> across(0.0, noise);
  std::uniform_real_distribution<double> clutter(-1.0, 1.0);
  std::vector<Vec2> local;
  for (double t = 0.0; t <= 3.0; t += 0.11) local.push_back({t, across(rng)});
  for (double t = 0.07; t <= 2.0; t += 0.13) local.push_back({across(rng), t});
  for (double t = 0.5; t <= 1.5; t += 0.12) local.push_back({t, 1.8 + across(rng)});
  for (int i = 0; i < 5; ++i) local.push_back({1.5 + 0.4 * clutter(rng), 0.9 + 0.4 * clutter(rng)});
  const Pose place{offset.x, offset.y, rotation};
  std::vector<Vec2> out;
  for (const Vec2& p : local) out.push_back(place.transform(p));
  return out;
}

TEST(WallAxes, WrapQuarterFoldsDirectionsIntoAQuarterTurn) {
  EXPECT_NEAR(wrap_quarter(0.1), 0.1, 1e-12);
  EXPECT_NEAR(wrap_quarter(0.1 + std::numbers::pi / 2.0), 0.1, 1e-12);
  EXPECT_NEAR(wrap_quarter(0.1 - 3.0 * std::numbers::pi), 0.1, 1e-12);
  EXPECT_NEAR(wrap_quarter(std::numbers::pi / 4.0 + 0.01), -std::numbers::pi / 4.0 + 0.01, 1e-12);
}

TEST(WallAxes, TheReaderFindsTheWallsDirectionAtAnyRotation) {
  WallAxisReader reader;
  for (double degrees : {0.0, 3.0, -7.5, 20.0, 44.0, 61.0, -130.0}) {
    const auto points = corner_points(degrees * kDegree, {2.0, -1.0}, 0.01, 5);
    const auto reading = reader.read(points, {});
    ASSERT_TRUE(reading) << degrees << " degrees";
    EXPECT_NEAR(wrap_quarter(reading->angle - degrees * kDegree), 0.0, 0.3 * kDegree)
        << degrees << " degrees";
    EXPECT_GE(reading->lines, 2);
    EXPECT_LT(reading->sigma, 0.5 * kDegree);
    EXPECT_GT(reading->sigma, 0.0);
  }
}

TEST(WallAxes, NoisierWallsGiveALessCertainReading) {
  WallAxisReader reader;
  const auto sharp = reader.read(corner_points(0.2, {}, 0.005, 3), {});
  const auto noisy = reader.read(corner_points(0.2, {}, 0.02, 3), {});
  ASSERT_TRUE(sharp);
  ASSERT_TRUE(noisy);
  EXPECT_GT(noisy->sigma, 1.2 * sharp->sigma);
  EXPECT_FALSE(reader.read(corner_points(0.2, {}, 0.06, 3), {}));  // no wall that straight
}

TEST(WallAxes, ScatteredPointsOrTooFewGiveNoReading) {
  WallAxisReader reader;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-3.0, 3.0);
  std::vector<Vec2> scattered;
  for (int i = 0; i < 60; ++i) scattered.push_back({coordinate(rng), coordinate(rng)});
  EXPECT_FALSE(reader.read(scattered, {}));
  const std::vector<Vec2> few{{0, 0}, {0.2, 0}, {0.4, 0}};
  EXPECT_FALSE(reader.read(few, {}));
  EXPECT_FALSE(reader.read({}, {}));
  const std::vector<Vec2> short_wall{{0, 0}, {0.1, 0}, {0.2, 0}, {0.3, 0}, {0.4, 0}, {0.5, 0}};
  EXPECT_FALSE(reader.read(short_wall, {}));  // below the minimum length
}

TEST(WallAxes, TheMapsAxesComeFromTheAnchorsOnceEnoughReadingsAgree) {
  MapWallAxes axes;
  std::mt19937 rng(3);
  std::normal_distribution<double> spread(0.0, 0.5 * kDegree);
  for (int i = 0; i < MapWallAxes::kMinReadings - 1; ++i) {
    // Readings of walls along 12 degrees and across it (estimated headings: a little off).
    axes.learn(wrap_quarter(12.0 * kDegree + (i % 2) * std::numbers::pi / 2.0 + spread(rng)));
  }
  axes.anchor(10.0 * kDegree, 1.0);
  EXPECT_FALSE(axes.axis());  // too few readings yet
  axes.learn(12.0 * kDegree);
  ASSERT_TRUE(axes.axis());
  EXPECT_NEAR(*axes.axis(), 10.0 * kDegree, 1e-9);  // the anchor's, not the readings'
}

TEST(WallAxes, NoAnchorNoAxes) {
  MapWallAxes axes;
  for (int i = 0; i < 50; ++i) axes.learn(0.0);
  EXPECT_FALSE(axes.axis());
}

TEST(WallAxes, OneBadAnchorDoesNotTiltTheAxes) {
  MapWallAxes axes;
  for (int i = 0; i < MapWallAxes::kMinReadings; ++i) axes.learn(0.0);
  axes.anchor(0.1 * kDegree, 1.0);
  axes.anchor(-0.2 * kDegree, 1.0);
  axes.anchor(6.9 * kDegree, 1.0);  // a shelf's edge read as a wall
  ASSERT_TRUE(axes.axis());
  EXPECT_NEAR(*axes.axis(), 0.1 * kDegree, 1e-9);
  // A reading on the far side of the quarter turn counts as the same direction.
  axes.anchor(wrap_quarter(0.15 * kDegree + std::numbers::pi / 2.0), 1.0);
  axes.anchor(-0.05 * kDegree + std::numbers::pi / 2.0, 1.0);
  ASSERT_TRUE(axes.axis());
  EXPECT_NEAR(*axes.axis(), 0.1 * kDegree, 1e-9);
}

TEST(WallAxes, WallsAtManyAnglesGiveTheMapNoAxes) {
  MapWallAxes axes;
  axes.anchor(0.0, 1.0);
  for (int i = 0; i < 200; ++i) axes.learn(wrap_quarter(i * 7.3 * kDegree));  // a ring's walls, every way
  EXPECT_EQ(axes.readings(), 200);
  EXPECT_FALSE(axes.axis());
}

TEST(WallAxes, AnchorsThatDisagreeGiveTheMapNoAxes) {
  // Robots whose trusted starts do not share one frame (odometry frames at their own starts, no
  // operator pose yet).
  MapWallAxes axes;
  for (int i = 0; i < MapWallAxes::kMinReadings; ++i) axes.learn(0.0);
  axes.anchor(0.0, 1.0);
  axes.anchor(30.0 * kDegree, 1.0);
  EXPECT_FALSE(axes.axis());
}

TEST(WallAxes, TheHeadingCorrectionTakesTheNearestQuarterTurn) {
  WallAxisReading reading;
  reading.angle = 0.3;
  // Walls along 0.3 + 1.2 = 1.5 rad in the map; the map's axes run along 0.1 and 0.1 + pi/2.
  EXPECT_NEAR(heading_correction(0.1, reading, 1.2), 0.1 + std::numbers::pi / 2.0 - 1.5, 1e-12);
  reading.angle = -0.02;
  EXPECT_NEAR(heading_correction(0.0, reading, std::numbers::pi - 0.01), 0.03, 1e-12);
}

}  // namespace
}  // namespace slam::correction
