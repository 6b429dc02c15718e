#include "eval/closure_audit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "eval/run_recorder.hpp"

namespace slam::bench {
namespace {

constexpr double kThreshold = 0.10;

// A robot truly at (5, 2) whose odometry drifted 0.3 m in x: it reports (5.3, 2).
constexpr Pose kOdometry{5.3, 2.0, 0.0};
constexpr Vec2 kTruth{5.0, 2.0};

CorrectionChange change(bool loop, Pose before, Pose after) {
  return {"r1", 1, 0, loop, before, after, kOdometry, kTruth, 0};
}

TEST(ClosureAudit, ALoopCorrectionTowardsTheTruthIsNotFalse) {
  const std::vector<CorrectionChange> changes = {change(true, Pose{}, Pose{-0.3, 0.0, 0.0})};
  const ClosureAudit audit = audit_corrections(changes, Pose{}, kThreshold);
  EXPECT_EQ(audit.loop_corrections, 1u);
  EXPECT_EQ(audit.false_closures, 0u);
  ASSERT_TRUE(audit.worst_increase_m.has_value());
  EXPECT_NEAR(*audit.worst_increase_m, -0.3, 1e-12);
  EXPECT_NEAR(audit.largest_loop_jump_m, 0.3, 1e-12);
}

TEST(ClosureAudit, ALoopCorrectionThatPullsTheRobotAwayIsFalse) {
  // Closed onto an identical room 2 m further on: the corrected pose lands 2 m from the truth.
  const std::vector<CorrectionChange> changes = {change(true, Pose{-0.3, 0.0, 0.0}, Pose{1.7, 0.0, 0.0})};
  const ClosureAudit audit = audit_corrections(changes, Pose{}, kThreshold);
  EXPECT_EQ(audit.false_closures, 1u);
  EXPECT_NEAR(*audit.worst_increase_m, 2.0, 1e-12);
  EXPECT_NEAR(audit.largest_jump_m, 2.0, 1e-12);
  ASSERT_EQ(audit.false_closure_list.size(), 1u);
  EXPECT_NEAR(audit.false_closure_list[0].errors.before_m, 0.0, 1e-12);
  EXPECT_NEAR(audit.false_closure_list[0].errors.after_m, 2.0, 1e-12);
}

TEST(ClosureAudit, AnIncreaseWithinTheThresholdIsNotFalse) {
  // Optimisation may trade a few centimetres at the robot for the rest of the graph.
  const std::vector<CorrectionChange> changes = {change(true, Pose{-0.3, 0.0, 0.0}, Pose{-0.3, 0.08, 0.0})};
  const ClosureAudit audit = audit_corrections(changes, Pose{}, kThreshold);
  EXPECT_EQ(audit.false_closures, 0u);
  EXPECT_NEAR(*audit.worst_increase_m, 0.08, 1e-12);
}

TEST(ClosureAudit, OnlyLoopChangesAreJudgedButEveryChangeCountsForTheJump) {
  const std::vector<CorrectionChange> changes = {
      change(false, Pose{}, Pose{3.0, 0.0, 0.0}),                 // a wild match: not a closure
      change(true, Pose{-0.3, 0.0, 0.0}, Pose{-0.25, 0.0, 0.0}),  // 5 cm worse
      change(true, Pose{-0.25, 0.0, 0.0}, Pose{0.0, 0.0, 0.0})};  // 25 cm worse: false
  const ClosureAudit audit = audit_corrections(changes, Pose{}, kThreshold);
  EXPECT_EQ(audit.corrections, 3u);
  EXPECT_EQ(audit.loop_corrections, 2u);
  EXPECT_EQ(audit.false_closures, 1u);
  EXPECT_EQ(audit.false_matches, 1u);  // the wild match, counted apart
  EXPECT_NEAR(*audit.worst_increase_m, 0.25, 1e-12);
  EXPECT_NEAR(audit.largest_jump_m, 3.0, 1e-12);
  EXPECT_NEAR(audit.largest_loop_jump_m, 0.25, 1e-12);
}

TEST(ClosureAudit, NoLoopChangeLeavesTheWorstIncreaseUnknown) {
  const std::vector<CorrectionChange> changes = {change(false, Pose{}, Pose{-0.3, 0.0, 0.0})};
  const ClosureAudit audit = audit_corrections(changes, Pose{}, kThreshold);
  EXPECT_EQ(audit.loop_corrections, 0u);
  EXPECT_FALSE(audit.worst_increase_m.has_value());
}

TEST(ClosureAudit, ARotationIsJudgedWhereTheRobotIs) {
  // A small rotation about the odometry origin moves a robot 5 m away by much more than it turns.
  const CorrectionChange c = change(true, Pose{-0.3, 0.0, 0.0}, Pose{-0.3, 0.0, 0.1});
  const ChangeErrors e = change_errors(c, Pose{});
  EXPECT_NEAR(e.before_m, 0.0, 1e-12);
  EXPECT_GT(e.after_m, 0.5);
  EXPECT_NEAR(e.jump_m, e.after_m, 1e-12);
}

TEST(ClosureAudit, TheAlignmentBringsTheMapFrameToTheWorld) {
  // The map frame is the world turned by 90 degrees: a right correction, seen through the
  // alignment, has no error; without it, it looks far off.
  const Pose map_from_world{1.0, -2.0, std::numbers::pi / 2};
  const Pose world_from_map = map_from_world.inverse();
  const Pose map_from_odom = map_from_world.compose(Pose{-0.3, 0.0, 0.0});
  const std::vector<CorrectionChange> changes = {change(true, map_from_world, map_from_odom)};
  EXPECT_NEAR(change_errors(changes[0], world_from_map).after_m, 0.0, 1e-12);
  const ClosureAudit audit = audit_corrections(changes, world_from_map, kThreshold);
  EXPECT_EQ(audit.false_closures, 0u);
  EXPECT_NEAR(*audit.worst_increase_m, -0.3, 1e-12);
}

// The recorder turns a stream of corrections into the changes scored above.
TEST(ClosureAudit, RecordedCorrectionSequenceIsScoredAgainstTheLatestTruth) {
  RunRecorder recorder(1'000'000'000, 0.2);
  recorder.on_correction("r1", Pose{0.1, 0.0, 0.0}, 1, false);  // no truth yet: not scored
  recorder.on_truth(7, {{"r1", Pose{kTruth.x, kTruth.y, 0.0}, kOdometry}});
  recorder.on_correction("r1", Pose{-0.2, 0.0, 0.0}, 2, false);
  recorder.on_correction("r1", Pose{-0.2, 0.0, 0.0}, 2, false);  // a repeat: not scored
  recorder.on_correction("r1", Pose{-0.3, 0.0, 0.0}, 4, true);   // version 3 missed
  recorder.on_correction("r1", Pose{1.7, 0.0, 0.0}, 5, true);    // the false closure
  recorder.on_correction("r2", Pose{}, 7, true);                 // what it replaced is unknown

  const std::vector<CorrectionChange> changes = recorder.correction_changes();
  ASSERT_EQ(changes.size(), 3u);
  EXPECT_EQ(changes[0].before, (Pose{0.1, 0.0, 0.0}));
  EXPECT_EQ(changes[1].before, (Pose{-0.2, 0.0, 0.0}));
  EXPECT_EQ(changes[1].versions_missed, 1u);
  EXPECT_EQ(recorder.unscored_corrections(), 3u);

  const ClosureAudit audit = audit_corrections(changes, Pose{}, kThreshold);
  EXPECT_EQ(audit.loop_corrections, 2u);
  EXPECT_EQ(audit.false_closures, 1u);
  EXPECT_NEAR(*audit.worst_increase_m, 2.0, 1e-12);
  EXPECT_EQ(audit.versions_missed, 1u);
  ASSERT_EQ(audit.false_closure_list.size(), 1u);
  EXPECT_EQ(audit.false_closure_list[0].version, 5u);
  EXPECT_EQ(audit.false_closure_list[0].truth_stamp_ns, 7);
}

TEST(ClosureAudit, TheFirstVersionReplacesTheIdentity) {
  RunRecorder recorder(1'000'000'000, 0.2);
  recorder.on_truth(0, {{"r1", Pose{kTruth.x, kTruth.y, 0.0}, kOdometry}});
  recorder.on_correction("r1", Pose{-0.3, 0.0, 0.0}, 1, true);
  const std::vector<CorrectionChange> changes = recorder.correction_changes();
  ASSERT_EQ(changes.size(), 1u);
  EXPECT_EQ(changes[0].before, Pose{});
  EXPECT_NEAR(change_errors(changes[0], Pose{}).before_m, 0.3, 1e-12);
  EXPECT_NEAR(change_errors(changes[0], Pose{}).after_m, 0.0, 1e-12);
}

}  // namespace
}  // namespace slam::bench
