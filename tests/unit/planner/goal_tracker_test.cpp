// GoalTracker: every mode's transitions, re-plan triggers and resend timing.
#include "planner/core/goal_tracker.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "grid_builder.hpp"

namespace slam::planner {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

Goal goal(GoalMode mode, Vec2 target = {}, double size = 0.0, SquareAnchor anchor = SquareAnchor::Corner) {
  return Goal{1, mode, target, size, anchor};
}

TEST(GoalTracker, IdleSendsNothing) {
  GoalTracker t({});
  t.set_goal(goal(GoalMode::Idle), {0, 0}, {0, 0});
  EXPECT_EQ(t.status(), GoalStatus::None);
  EXPECT_FALSE(t.current_waypoint());
  EXPECT_FALSE(t.should_send(0));
}

TEST(GoalTracker, DirectDrivesToTargetAndReaches) {
  GoalTracker t({});
  t.set_goal(goal(GoalMode::Direct, {2, 0}), {0, 0}, {0, 0});
  EXPECT_EQ(t.status(), GoalStatus::Active);
  EXPECT_EQ(t.current_waypoint().value(), (Vec2{2, 0}));
  EXPECT_FALSE(t.needs_plan());
  t.update_position({1.0, 0.0});
  EXPECT_EQ(t.status(), GoalStatus::Active);
  t.update_position({1.9, 0.05});
  EXPECT_EQ(t.status(), GoalStatus::Reached);
  EXPECT_FALSE(t.should_send(10 * kSecond));
}

TEST(GoalTracker, SquareFromCorner) {
  GoalTracker t({});
  t.set_goal(goal(GoalMode::Square, {1, 1}, 2.0, SquareAnchor::Corner), {0, 0}, {0, 0});
  const std::vector<Vec2> want{{1, 1}, {3, 1}, {3, 3}, {1, 3}, {1, 1}};
  EXPECT_EQ(t.waypoints(), want);
  for (size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(t.current_index(), i);
    EXPECT_EQ(t.status(), GoalStatus::Active);
    t.update_position(want[i]);
  }
  EXPECT_EQ(t.status(), GoalStatus::Reached);
}

TEST(GoalTracker, SquareCentred) {
  GoalTracker t({});
  t.set_goal(goal(GoalMode::Square, {1, 1}, 2.0, SquareAnchor::Centred), {5, 5}, {0, 0});
  const std::vector<Vec2> want{{0, 0}, {2, 0}, {2, 2}, {0, 2}, {0, 0}};
  EXPECT_EQ(t.waypoints(), want);
  EXPECT_EQ(t.target(), (Vec2{1, 1}));
}

TEST(GoalTracker, RejectsBadGoals) {
  EXPECT_FALSE(validate(goal(GoalMode::Square, {0, 0}, 0.0)));
  EXPECT_FALSE(validate(goal(GoalMode::Direct, {std::nan(""), 0})));
  EXPECT_TRUE(validate(goal(GoalMode::Square, {0, 0}, 1.0)));
  TrackerConfig c;
  c.resend_period_s = 0;
  EXPECT_FALSE(validate(c));
}

TEST(GoalTracker, PlannedFollowsPathAndAdvances) {
  GoalTracker t({});
  t.set_goal(goal(GoalMode::Planned, {4, 4}), {0, 0}, {0, 0});
  EXPECT_TRUE(t.needs_plan());
  EXPECT_FALSE(t.current_waypoint());
  EXPECT_EQ(t.plan_target(), (Vec2{4, 4}));
  t.set_path({{0, 0}, {4, 0}, {4, 4}});
  EXPECT_FALSE(t.needs_plan());
  EXPECT_EQ(t.current_waypoint().value(), (Vec2{4, 0}));
  t.update_position({2, 0.1});
  EXPECT_EQ(t.current_index(), 0u);
  t.update_position({4, 0.1});
  EXPECT_EQ(t.current_waypoint().value(), (Vec2{4, 4}));
  EXPECT_EQ(t.remaining().size(), 1u);
  t.update_position({4, 4});
  EXPECT_EQ(t.status(), GoalStatus::Reached);
}

TEST(GoalTracker, ReplansWhenRobotStrays) {
  TrackerConfig c;
  c.stray_threshold_m = 0.5;
  GoalTracker t(c);
  t.set_goal(goal(GoalMode::Planned, {4, 0}), {0, 0}, {0, 0});
  t.set_path({{0, 0}, {4, 0}});
  t.update_position({1, 0.4});
  EXPECT_FALSE(t.needs_plan());
  t.update_position({1, 0.6});
  EXPECT_TRUE(t.needs_plan());
}

TEST(GoalTracker, ReplansWhenGridBlocksRemainingPath) {
  PlanningGrid g = test::uniform_grid(10, 10, kCellFree);
  GoalTracker t({});
  t.set_goal(goal(GoalMode::Planned, {8.5, 8.5}), {0.5, 0.5}, {0.5, 0.5});
  t.set_path({{0.5, 0.5}, {8.5, 0.5}, {8.5, 8.5}});
  t.check_path(g, UnknownPolicy::Blocked);
  EXPECT_FALSE(t.needs_plan());
  g.set({8, 5}, kCellOccupied);  // on the second leg, not yet driven
  t.check_path(g, UnknownPolicy::Blocked);
  EXPECT_TRUE(t.needs_plan());
  t.set_path({{0.5, 0.5}, {7.5, 0.5}, {7.5, 8.5}, {8.5, 8.5}});
  EXPECT_FALSE(t.needs_plan());
  EXPECT_EQ(t.current_index(), 0u);
}

TEST(GoalTracker, PlanFailureFailsWithReason) {
  GoalTracker t({});
  t.set_goal(goal(GoalMode::Planned, {4, 4}), {0, 0}, {0, 0});
  t.plan_failed("NO_PATH: walled in");
  EXPECT_EQ(t.status(), GoalStatus::Failed);
  EXPECT_EQ(t.reason(), "NO_PATH: walled in");
  EXPECT_FALSE(t.needs_plan());
  EXPECT_FALSE(t.should_send(0));
}

TEST(GoalTracker, HomeGoesToFirstSeenPosition) {
  GoalTracker t({});
  t.set_goal(goal(GoalMode::Home, {99, 99}), {5, 5}, {1, 2});
  EXPECT_TRUE(t.needs_plan());
  EXPECT_EQ(t.plan_target(), (Vec2{1, 2}));
  t.set_path({{5, 5}, {1, 2}});
  t.update_position({1, 2});
  EXPECT_EQ(t.status(), GoalStatus::Reached);
}

TEST(GoalTracker, StopHoldsPositionAndKeepsSending) {
  GoalTracker t({});
  t.set_goal(goal(GoalMode::Stop, {9, 9}), {3, 4}, {0, 0});
  EXPECT_EQ(t.current_waypoint().value(), (Vec2{3, 4}));
  EXPECT_EQ(t.status(), GoalStatus::Reached);
  EXPECT_TRUE(t.should_send(0));
  EXPECT_FALSE(t.should_send(kSecond / 2));
  EXPECT_TRUE(t.should_send(kSecond));
  t.update_position({3.5, 4});  // drifting does not move the hold point
  EXPECT_EQ(t.current_waypoint().value(), (Vec2{3, 4}));
}

TEST(GoalTracker, ResendsEveryPeriodAndAtOnceOnChange) {
  TrackerConfig c;
  c.resend_period_s = 2.0;
  GoalTracker t(c);
  t.set_goal(goal(GoalMode::Square, {0, 0}, 1.0), {5, 5}, {0, 0});
  EXPECT_TRUE(t.should_send(100));
  EXPECT_FALSE(t.should_send(100 + kSecond));
  EXPECT_TRUE(t.should_send(100 + 2 * kSecond));
  EXPECT_FALSE(t.should_send(100 + 2 * kSecond + 1));
  t.update_position({0, 0});  // next corner: send now, not in two seconds
  EXPECT_TRUE(t.should_send(100 + 2 * kSecond + 2));
  EXPECT_FALSE(t.should_send(100 + 3 * kSecond));
}

TEST(GoalTracker, ExploreAsksForFrontiersThenGoesHome) {
  GoalTracker t({});
  t.set_goal(goal(GoalMode::Explore), {1, 1}, {0, 0});
  EXPECT_TRUE(t.wants_frontier());
  EXPECT_FALSE(t.needs_plan());
  t.set_frontier({5, 1});
  EXPECT_FALSE(t.wants_frontier());
  EXPECT_TRUE(t.needs_plan());
  t.set_path({{1, 1}, {5, 1}});
  t.update_position({5, 1});
  EXPECT_EQ(t.status(), GoalStatus::Active);  // frontier reached: exploring goes on
  EXPECT_TRUE(t.wants_frontier());
  t.set_frontier({5, 5});
  t.plan_failed("NO_PATH");  // unreachable frontier: ask for another, do not fail
  EXPECT_EQ(t.status(), GoalStatus::Active);
  EXPECT_TRUE(t.wants_frontier());
  t.exploration_complete();
  EXPECT_TRUE(t.homing());
  EXPECT_TRUE(t.needs_plan());
  EXPECT_EQ(t.plan_target(), (Vec2{0, 0}));
  t.set_path({{5, 1}, {0, 0}});
  t.update_position({0, 0});
  EXPECT_EQ(t.status(), GoalStatus::Reached);
}

TEST(GoalTracker, AnEscapeLegFromAnInflatedStartIsNoReasonToReplan) {
  const PlanningGrid g = test::grid_from_art({
      "#i......",
      "#i......",
  });
  GoalTracker t({});
  t.set_goal(goal(GoalMode::Planned, {6.5, 1.5}), {1.3, 1.5}, {1.3, 1.5});
  t.set_path({{1.3, 1.5}, {2.5, 1.5}, {6.5, 1.5}});
  t.check_path(g, UnknownPolicy::Blocked);
  EXPECT_FALSE(t.needs_plan());
  // A wall across a later leg still is.
  PlanningGrid blocked = g;
  blocked.set({4, 1}, kCellOccupied);
  t.check_path(blocked, UnknownPolicy::Blocked);
  EXPECT_TRUE(t.needs_plan());
}

TEST(GoalTracker, ReportsTheFrontierItArrivedAtOnce) {
  GoalTracker t({});
  t.set_goal(goal(GoalMode::Explore), {1, 1}, {0, 0});
  t.set_frontier({5, 1});
  t.set_path({{1, 1}, {5, 1}});
  EXPECT_FALSE(t.take_reached_frontier());
  t.update_position({5, 1});
  EXPECT_EQ(t.take_reached_frontier(), (Vec2{5, 1}));
  EXPECT_FALSE(t.take_reached_frontier());
  // Dropped without arriving: nothing to report.
  t.set_frontier({9, 1});
  t.drop_frontier();
  EXPECT_FALSE(t.take_reached_frontier());
}

TEST(GoalTracker, ARevisitDrivesBackThenAsksForAFrontierAgain) {
  GoalTracker t({});
  t.set_goal(goal(GoalMode::Explore), {1, 1}, {0, 0});
  t.set_frontier({5, 1});
  t.set_path({{1, 1}, {5, 1}});
  t.update_position({3, 1});
  t.revisit({1, 1});
  EXPECT_TRUE(t.revisiting());
  EXPECT_FALSE(t.has_frontier());
  EXPECT_FALSE(t.wants_frontier());
  EXPECT_TRUE(t.target_stood_on());
  ASSERT_TRUE(t.needs_plan());
  EXPECT_EQ(t.plan_target(), (Vec2{1, 1}));
  t.set_path({{3, 1}, {1, 1}});
  EXPECT_EQ(t.current_waypoint(), (Vec2{1, 1}));
  t.update_position({1, 1});
  // Back where it was localised: exploring goes on, and the place is no frontier to give up.
  EXPECT_FALSE(t.revisiting());
  EXPECT_TRUE(t.wants_frontier());
  EXPECT_EQ(t.status(), GoalStatus::Active);
  EXPECT_FALSE(t.take_reached_frontier());
  // Ended early (tied again on the way): the same.
  t.set_frontier({5, 1});
  t.revisit({1, 1});
  t.drop_frontier();
  EXPECT_FALSE(t.revisiting());
  EXPECT_TRUE(t.wants_frontier());
}

TEST(GoalTracker, OnlyAnExploringRobotRevisits) {
  GoalTracker t({});
  t.set_goal(goal(GoalMode::Planned, {5, 1}), {1, 1}, {0, 0});
  t.revisit({0, 0});
  EXPECT_FALSE(t.revisiting());
  EXPECT_EQ(t.plan_target(), (Vec2{5, 1}));
  t.set_goal(goal(GoalMode::Explore), {1, 1}, {0, 0});
  t.exploration_complete();  // homing
  t.revisit({0, 0});
  EXPECT_FALSE(t.revisiting());
  EXPECT_TRUE(t.homing());
}

}  // namespace
}  // namespace slam::planner
