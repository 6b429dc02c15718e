#include "pose_correction/correction_schedule.hpp"

#include <gtest/gtest.h>

namespace slam::correction {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

ScheduleOptions options() {
  ScheduleOptions o;
  o.load_backlog = 10;
  o.shed_backlog = 100;
  o.max_backlog = 1000;
  o.ties_every = 3;
  o.wide_interval_s = 5.0;
  o.wide_per_s = 2.0;
  return o;
}

TEST(CorrectionSchedule, TheBacklogSetsTheLoad) {
  CorrectionSchedule schedule(options());
  schedule.begin_pass(9, 0);
  EXPECT_EQ(schedule.load(), Load::Normal);
  schedule.begin_pass(10, 0);
  EXPECT_EQ(schedule.load(), Load::Loaded);
  schedule.begin_pass(100, 0);
  EXPECT_EQ(schedule.load(), Load::Shedding);
}

TEST(CorrectionSchedule, NormalLoadAllowsEveryTieAndWideSearch) {
  CorrectionSchedule schedule(options());
  CorrectionSchedule::RobotState robot;
  schedule.begin_pass(0, 0);
  for (int i = 0; i < 20; ++i) {
    EXPECT_TRUE(schedule.allow_tie(robot));
    EXPECT_TRUE(schedule.allow_wide(robot, i));
  }
}

TEST(CorrectionSchedule, UnderLoadARobotTiesEveryKthKeyframe) {
  CorrectionSchedule schedule(options());
  CorrectionSchedule::RobotState a, b;
  schedule.begin_pass(50, 0);
  int ties_a = 0, ties_b = 0;
  for (int i = 0; i < 9; ++i) ties_a += schedule.allow_tie(a) ? 1 : 0;
  for (int i = 0; i < 3; ++i) ties_b += schedule.allow_tie(b) ? 1 : 0;
  EXPECT_EQ(ties_a, 3);
  EXPECT_EQ(ties_b, 1);  // per robot: another robot's ties do not use up its turn
}

TEST(CorrectionSchedule, UnderLoadWideSearchesKeepTheRobotIntervalAndTheFleetRate) {
  CorrectionSchedule schedule(options());
  CorrectionSchedule::RobotState a, b, c;
  schedule.begin_pass(50, 0);
  schedule.begin_pass(50, kSecond);  // one second of allowance: two wide searches
  EXPECT_TRUE(schedule.allow_wide(a, kSecond));
  EXPECT_FALSE(schedule.allow_wide(a, 2 * kSecond)) << "robot interval not kept";
  EXPECT_TRUE(schedule.allow_wide(b, kSecond));
  EXPECT_FALSE(schedule.allow_wide(c, kSecond)) << "fleet rate not kept";
  schedule.begin_pass(50, 2 * kSecond);
  EXPECT_TRUE(schedule.allow_wide(c, 2 * kSecond));
  EXPECT_FALSE(schedule.allow_wide(a, 5 * kSecond));
  schedule.begin_pass(50, 7 * kSecond);
  EXPECT_TRUE(schedule.allow_wide(a, 6 * kSecond));
}

TEST(CorrectionSchedule, AQuietSpellBuysNoBurstOfWideSearches) {
  CorrectionSchedule schedule(options());
  schedule.begin_pass(50, 0);
  schedule.begin_pass(50, 100 * kSecond);
  int granted = 0;
  for (int r = 0; r < 10; ++r) {
    CorrectionSchedule::RobotState robot;
    granted += schedule.allow_wide(robot, 100 * kSecond) ? 1 : 0;
  }
  EXPECT_EQ(granted, 2);
}

TEST(CorrectionSchedule, SheddingAllowsNoTieAndNoWideSearch) {
  CorrectionSchedule schedule(options());
  CorrectionSchedule::RobotState robot;
  schedule.begin_pass(100, 0);
  schedule.begin_pass(100, 10 * kSecond);
  for (int i = 0; i < 5; ++i) {
    EXPECT_FALSE(schedule.allow_tie(robot));
    EXPECT_FALSE(schedule.allow_wide(robot, 10 * kSecond));
  }
}

TEST(CorrectionSchedule, OnlyTheBacklogBeyondTheCapOverflows) {
  const CorrectionSchedule schedule(options());
  EXPECT_EQ(schedule.overflow(1000), 0u);
  EXPECT_EQ(schedule.overflow(1250), 250u);
}

TEST(CorrectionSchedule, AnOptimisationIsFollowedByIdleTimeInProportionToItsDuration) {
  ScheduleOptions o = options();
  o.optimise_idle_factor = 4;
  CorrectionSchedule schedule(o);
  EXPECT_TRUE(schedule.allow_optimisation(0));               // none ran yet
  schedule.optimisation_landed(10 * kSecond, 12 * kSecond);  // took 2 s: none for 8 s after it landed
  EXPECT_FALSE(schedule.allow_optimisation(12 * kSecond));
  EXPECT_FALSE(schedule.allow_optimisation(20 * kSecond - 1));
  EXPECT_TRUE(schedule.allow_optimisation(20 * kSecond));
  schedule.optimisation_landed(20 * kSecond, 20 * kSecond);  // instant: the next may start at once
  EXPECT_TRUE(schedule.allow_optimisation(20 * kSecond));
}

}  // namespace
}  // namespace slam::correction
