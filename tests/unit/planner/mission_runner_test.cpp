// MissionRunner: legs in order, looping, skipping unreachable waypoints, adopting another planner's progress.
#include "planner/core/mission_runner.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace slam::planner {
namespace {

Mission three_points(bool loop) {
  return Mission{42, {{1, 0}, {2, 0}, {3, 0}}, loop};
}

TEST(MissionRunner, RunsEachWaypointOnceThenIsDone) {
  MissionRunner runner;
  const Goal first = runner.start("r", three_points(false));
  EXPECT_EQ(first.goal_id, 42u);
  EXPECT_EQ(first.mode, GoalMode::Planned);
  EXPECT_EQ(first.target, (Vec2{1, 0}));
  EXPECT_EQ(runner.take_changed(), std::vector<std::string>{"r"});

  auto next = runner.leg_ended("r", true, "");
  ASSERT_TRUE(next);
  EXPECT_EQ(next->target, (Vec2{2, 0}));
  next = runner.leg_ended("r", true, "");
  ASSERT_TRUE(next);
  EXPECT_EQ(next->target, (Vec2{3, 0}));
  EXPECT_FALSE(runner.leg_ended("r", true, ""));
  const auto* r = runner.find("r");
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->progress.status, MissionStatus::Done);
  EXPECT_EQ(r->progress.laps, 1u);
  EXPECT_FALSE(runner.active("r"));
  // Over: a late outcome changes nothing.
  runner.take_changed();
  EXPECT_FALSE(runner.leg_ended("r", true, ""));
  EXPECT_TRUE(runner.take_changed().empty());
}

TEST(MissionRunner, AForgottenRobotsMissionGoesUnreported) {
  MissionRunner runner;
  runner.start("r", three_points(true));
  runner.forget("r");
  EXPECT_EQ(runner.find("r"), nullptr);
  EXPECT_TRUE(runner.take_changed().empty()) << "nothing to publish for a forgotten robot";
  EXPECT_FALSE(runner.leg_ended("r", true, ""));
}

TEST(MissionRunner, ALoopWrapsToTheFirstWaypointAndCountsLaps) {
  MissionRunner runner;
  runner.start("r", three_points(true));
  for (int leg = 0; leg < 2; ++leg) ASSERT_TRUE(runner.leg_ended("r", true, ""));
  const auto wrapped = runner.leg_ended("r", true, "");
  ASSERT_TRUE(wrapped);
  EXPECT_EQ(wrapped->target, (Vec2{1, 0}));
  EXPECT_EQ(runner.find("r")->progress.current, 0u);
  EXPECT_EQ(runner.find("r")->progress.laps, 1u);
  EXPECT_TRUE(runner.active("r"));
}

TEST(MissionRunner, AnUnreachableWaypointIsSkippedAndReported) {
  MissionRunner runner;
  runner.start("r", three_points(true));
  const auto next = runner.leg_ended("r", false, "GOAL_BLOCKED: inside an obstacle");
  ASSERT_TRUE(next);
  EXPECT_EQ(next->target, (Vec2{2, 0}));
  EXPECT_EQ(runner.find("r")->progress.reason, "waypoint 0 skipped: GOAL_BLOCKED: inside an obstacle");
  EXPECT_TRUE(runner.active("r"));
}

TEST(MissionRunner, FailsWhenEveryWaypointFailedInARow) {
  MissionRunner runner;
  runner.start("r", three_points(true));
  ASSERT_TRUE(runner.leg_ended("r", true, ""));
  ASSERT_TRUE(runner.leg_ended("r", false, "NO_PATH"));
  ASSERT_TRUE(runner.leg_ended("r", true, ""));  // one reached: the count starts again
  ASSERT_TRUE(runner.leg_ended("r", false, "NO_PATH"));
  ASSERT_TRUE(runner.leg_ended("r", false, "NO_PATH"));
  EXPECT_FALSE(runner.leg_ended("r", false, "NO_PATH"));
  EXPECT_EQ(runner.find("r")->progress.status, MissionStatus::Failed);
  EXPECT_EQ(runner.find("r")->progress.reason, "no waypoint reachable: NO_PATH");
}

TEST(MissionRunner, APatrolThatCannotMoveFailsAfterAWholePass) {
  // Only the waypoint the robot stands on is reachable: its leg ends at once, lap after lap.
  MissionRunner runner;
  runner.start("r", three_points(true));
  ASSERT_TRUE(runner.leg_ended("r", true, ""));
  ASSERT_TRUE(runner.leg_ended("r", false, "GOAL_BLOCKED"));
  EXPECT_FALSE(runner.leg_ended("r", false, "GOAL_BLOCKED"));
  EXPECT_EQ(runner.find("r")->progress.status, MissionStatus::Failed);
  EXPECT_EQ(runner.find("r")->progress.reason,
            "fewer than two waypoints reachable in a pass (waypoint 2 skipped: GOAL_BLOCKED)");
  // A pass that began mid-way (resumed at waypoint 2) is not judged.
  runner.start("r", three_points(true), MissionProgress{2, 0, MissionStatus::Active, ""});
  EXPECT_TRUE(runner.leg_ended("r", true, ""));
  EXPECT_TRUE(runner.active("r"));
}

TEST(MissionRunner, CancelEndsOnlyRunningMissions) {
  MissionRunner runner;
  runner.start("a", three_points(true));
  runner.start("b", three_points(false));
  EXPECT_TRUE(runner.cancel("a"));
  EXPECT_FALSE(runner.cancel("a"));
  EXPECT_FALSE(runner.cancel("nobody"));
  EXPECT_EQ(runner.find("a")->progress.status, MissionStatus::Cancelled);
  EXPECT_EQ(runner.cancel_all(), std::vector<std::string>{"b"});
  EXPECT_FALSE(runner.leg_ended("b", true, ""));
}

TEST(MissionRunner, AdoptsProgressAndGivesTheNewLegOnlyWhenTheWaypointMoved) {
  MissionRunner runner;
  runner.start("r", three_points(true));
  runner.take_changed();
  const auto moved = runner.adopt("r", MissionProgress{2, 3, MissionStatus::Active, ""});
  ASSERT_TRUE(moved);
  EXPECT_EQ(moved->target, (Vec2{3, 0}));
  EXPECT_EQ(runner.find("r")->progress.laps, 3u);
  EXPECT_EQ(runner.take_changed(), std::vector<std::string>{"r"});
  // The same report again (an echo): nothing changes.
  EXPECT_FALSE(runner.adopt("r", MissionProgress{2, 3, MissionStatus::Active, ""}));
  EXPECT_TRUE(runner.take_changed().empty());
  EXPECT_FALSE(runner.adopt("r", MissionProgress{2, 3, MissionStatus::Done, ""}));
  EXPECT_FALSE(runner.active("r"));
}

TEST(MissionRunner, ResumesAtTheGivenProgress) {
  MissionRunner runner;
  const Goal leg = runner.start("r", three_points(true), MissionProgress{1, 4, MissionStatus::Active, ""});
  EXPECT_EQ(leg.target, (Vec2{2, 0}));
  EXPECT_EQ(runner.find("r")->progress.laps, 4u);
}

TEST(MissionValidate, RefusesWhatCannotRun) {
  EXPECT_TRUE(validate(three_points(true)));
  EXPECT_FALSE(validate(Mission{1, {}, false}));
  EXPECT_FALSE(validate(Mission{1, {{1, 1}}, true}));
  EXPECT_TRUE(validate(Mission{1, {{1, 1}}, false}));
  EXPECT_FALSE(validate(Mission{1, {{1, 1}, {0.0 / 0.0, 1}}, false}));
  EXPECT_FALSE(validate(Mission{1, std::vector<Vec2>(kMaxMissionWaypoints + 1, Vec2{1, 1}), false}));
  EXPECT_FALSE(validate(three_points(false), MissionProgress{3, 0, MissionStatus::Active, ""}));
}

}  // namespace
}  // namespace slam::planner
