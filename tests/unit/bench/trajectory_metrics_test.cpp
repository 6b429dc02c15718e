#include "eval/trajectory_metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace slam::bench {
namespace {

std::vector<Vec2> loop_track() {
  std::vector<Vec2> out;
  for (int i = 0; i < 40; ++i) out.push_back({3.0 + 2.0 * std::cos(0.2 * i), 1.0 + std::sin(0.3 * i)});
  return out;
}

TEST(TrajectoryErrors, ConstantOffsetGivesThatErrorEverywhere) {
  const std::vector<Vec2> truth = loop_track();
  const std::vector<Vec2> estimate = transformed(Pose{0.1, 0.0, 0.0}, truth);
  const ErrorStats s = position_errors(estimate, truth);
  EXPECT_EQ(s.count, truth.size());
  EXPECT_NEAR(s.rmse, 0.1, 1e-12);
  EXPECT_NEAR(s.max, 0.1, 1e-12);
  EXPECT_NEAR(s.mean, 0.1, 1e-12);
}

TEST(TrajectoryErrors, RmseWeighsLargeErrorsAndMaxIsTheLargest) {
  const std::vector<double> errors = {0.3, 0.4};
  const ErrorStats s = summarise(errors);
  EXPECT_NEAR(s.rmse, std::sqrt((0.09 + 0.16) / 2.0), 1e-12);
  EXPECT_NEAR(s.mean, 0.35, 1e-12);
  EXPECT_DOUBLE_EQ(s.max, 0.4);
  EXPECT_EQ(summarise({}).count, 0u);
}

TEST(TrajectoryErrors, FitRecoversAKnownRigidTransform) {
  const std::vector<Vec2> estimate = loop_track();
  const Pose known{1.5, -2.25, 0.7};
  const Pose fit = fit_rigid(estimate, transformed(known, estimate));
  EXPECT_NEAR(fit.x, known.x, 1e-9);
  EXPECT_NEAR(fit.y, known.y, 1e-9);
  EXPECT_NEAR(fit.theta, known.theta, 1e-9);
}

TEST(TrajectoryErrors, AlignmentRemovesTheMapFrameButNotTheError) {
  const std::vector<Vec2> truth = loop_track();
  const Pose map_from_world{-4.0, 2.0, 2.5};
  std::vector<TrajectorySample> samples;
  for (size_t i = 0; i < truth.size(); ++i) {
    // Corrected: exact but in a rotated map frame. Raw: robot "a" exact in its own frame, robot
    // "b" 0.2 m off on every second sample (not a rigid error: alignment cannot remove it).
    const std::string robot = i % 2 == 0 ? "a" : "b";
    const Vec2 off = robot == "b" && i % 4 == 1 ? Vec2{0.2, 0.0} : Vec2{};
    samples.push_back(
        {robot, truth[i], map_from_world.transform(truth[i]) + off, map_from_world.transform(truth[i])});
  }
  const TrajectoryErrors unaligned = trajectory_errors(samples, false);
  EXPECT_GT(unaligned.corrected.rmse, 1.0);
  const TrajectoryErrors aligned = trajectory_errors(samples, true);
  EXPECT_NEAR(aligned.corrected.rmse, 0.0, 1e-9);
  EXPECT_NEAR(aligned.alignment.compose(map_from_world).x, 0.0, 1e-9);
  EXPECT_NEAR(aligned.alignment.compose(map_from_world).theta, 0.0, 1e-9);
  EXPECT_GT(aligned.raw.max, 0.05);
  EXPECT_LT(aligned.raw.max, 0.2);
}

}  // namespace
}  // namespace slam::bench
