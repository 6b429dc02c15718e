#include "eval/run_recorder.hpp"

#include <gtest/gtest.h>

namespace slam::bench {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

TEST(RunRecorder, SamplesOncePerPeriodWhileStartedAndAppliesTheCorrection) {
  RunRecorder recorder(kSecond, 0.2);
  const auto truth_at = [&](int64_t t, double x) {
    recorder.on_truth(t, {{"r1", Pose{x, 0.0, 0.0}, Pose{x + 0.5, 0.0, 0.0}}});
  };
  truth_at(0, 0.0);  // before start: a start position, no sample
  recorder.start();
  recorder.on_correction("r1", Pose{-0.5, 0.0, 0.0}, 3, false);
  for (int i = 1; i <= 20; ++i) truth_at(i * kSecond / 4, 0.1 * i);  // 4 per period
  recorder.stop();
  truth_at(10 * kSecond, 9.0);

  const auto samples = recorder.samples();
  ASSERT_EQ(samples.size(), 5u);
  for (const TrajectorySample& s : samples) {
    EXPECT_NEAR(s.raw.x - s.truth.x, 0.5, 1e-12);
    EXPECT_NEAR(s.corrected.x, s.truth.x, 1e-12);
  }
  EXPECT_EQ(recorder.true_starts(), (std::vector<Vec2>{{0.0, 0.0}}));
  EXPECT_EQ(recorder.corrected_robots(), 1u);
  EXPECT_TRUE(recorder.published_vs_truth().empty());  // no RobotState heard
  // The truth of the sampled instants, for a replay: stamps and both poses as heard.
  const auto truth = recorder.truth_samples();
  ASSERT_EQ(truth.size(), samples.size());
  EXPECT_EQ(truth.front().stamp_ns, kSecond / 4);
  EXPECT_EQ(truth.back().stamp_ns, 17 * kSecond / 4);
  EXPECT_EQ(truth.back().truth.robot_id, "r1");
  EXPECT_NEAR(truth.back().truth.reported_pose.x, 2.2, 1e-12);
}

TEST(RunRecorder, APlacementIsTimedFromTheRobotsFirstTruthAndScoredAgainstIt) {
  RunRecorder recorder(kSecond, 0.2);
  // r1's odometry starts at (0, 0) where it truly stands at (3, 1): map <- odom is a shift by (3, 1).
  const auto truth_at = [&](int64_t t, double x) {
    recorder.on_truth(t, {{"r1", Pose{3.0 + x, 1.0, 0.0}, Pose{x, 0.0, 0.0}}});
  };
  recorder.start();
  truth_at(2 * kSecond, 0.0);
  recorder.on_correction("r1", Pose{}, 1, false, false);  // searched for: no placement
  for (int i = 1; i <= 12; ++i) truth_at(2 * kSecond + i * kSecond / 2, 0.1 * i);
  recorder.on_correction("r1", Pose{3.02, 1.0, 0.0}, 2, false, true);  // placed, 2 cm off, 6 s in
  truth_at(9 * kSecond, 1.4);
  recorder.on_correction("r1", Pose{3.0, 1.0, 0.0}, 3, false, true);  // still placed: not a second one
  truth_at(10 * kSecond, 1.5);
  recorder.stop();

  const auto placements = recorder.placements();
  ASSERT_EQ(placements.size(), 1u);
  EXPECT_EQ(placements[0].robot_id, "r1");
  EXPECT_NEAR(placements[0].after_s, 6.0, 1e-9);
  EXPECT_NEAR(placements[0].error_m, 0.02, 1e-9);
  // Only the samples from the placement on are the placed robot's.
  const auto placed = recorder.placed_samples();
  ASSERT_FALSE(placed.empty());
  EXPECT_LT(placed.size(), recorder.samples().size());
  for (const TrajectorySample& s : placed) EXPECT_NEAR(s.corrected.x, s.truth.x, 0.021);
}

TEST(RunRecorder, AnArrivalTakesTheNextTruthSample) {
  RunRecorder recorder(kSecond, 0.2);
  recorder.start();
  const std::vector<Vec2> path = {{1.0, 0.0}, {2.0, 0.0}};
  recorder.on_path("r1", {1, path, 0});
  recorder.on_published_pose("r1", {1.0, 0.1});
  recorder.on_path("r1", {1, path, 1});
  EXPECT_TRUE(recorder.arrivals().empty());  // waits for the truth
  recorder.on_truth(kSecond, {{"r1", Pose{1.0, 0.3, 0.0}, Pose{1.0, 0.1, 0.0}}});
  const auto arrivals = recorder.arrivals();
  ASSERT_EQ(arrivals.size(), 1u);
  EXPECT_NEAR(arrivals[0].true_distance_m, 0.3, 1e-12);
  EXPECT_NEAR(arrivals[0].reported_distance_m, 0.1, 1e-12);
}

}  // namespace
}  // namespace slam::bench
