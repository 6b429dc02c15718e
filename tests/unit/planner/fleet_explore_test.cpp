// Fleet exploration edge cases met with real robots: starting in an inflated or unexplored cell,
// frontiers that stay after a robot reached them, and when a robot may call exploration done.
#include <gtest/gtest.h>

#include "grid_builder.hpp"
#include "planner/core/fleet.hpp"

namespace slam::planner {
namespace {

constexpr int64_t kSecond = 1'000'000'000;
constexpr double kRes = 0.1;  // the default escape radius (0.5 m) is five cells

Goal explore_goal() {
  return Goal{1, GoalMode::Explore, {}, 0, {}};
}

// A known strip along a wall, unexplored beyond: one frontier row at y = 0.45 m.
PlanningGrid strip() {
  return test::grid_from_art(
      {
          "????????????????????",
          "....................",
          "....................",
          "....................",
          "iiiiiiiiiiiiiiiiiiii",
          "####################",
      },
      kRes);
}

TEST(FleetExplore, ARobotInAnInflatedCellStillExplores) {
  const PlanningGrid g = strip();
  Fleet fleet({});
  const Vec2 start{1.05, 0.15};  // in the inflated row beside the wall
  fleet.observe("a", start);
  fleet.grid_changed(g, std::nullopt);
  ASSERT_TRUE(fleet.set_goal("a", explore_goal()));
  fleet.tick(g, 0);
  const GoalTracker* t = fleet.tracker("a");
  ASSERT_TRUE(t->has_frontier());
  EXPECT_FALSE(t->homing());
  ASSERT_GE(t->waypoints().size(), 2u);
  EXPECT_EQ(t->waypoints().front(), (Vec2{1.05, 0.25}));  // the escape leg comes first
  EXPECT_FALSE(fleet.exploration_complete());
  EXPECT_EQ(fleet.blacklist().size(), 0u);
}

TEST(FleetExplore, ARobotThatLostItsLocalisationGoesBackThenExploresOn) {
  const PlanningGrid g = strip();
  Fleet fleet({});
  fleet.observe_uncertainty("ghost", 0.5);  // unknown robots are ignored
  EXPECT_EQ(fleet.size(), 0u);
  fleet.observe("a", {0.55, 0.25});
  fleet.observe_uncertainty("a", 0.08);
  fleet.observe_uncertainty("a", 0.04);  // shrank: tied to the old map here
  fleet.grid_changed(g, std::nullopt);
  ASSERT_TRUE(fleet.set_goal("a", explore_goal()));
  fleet.tick(g, 0);
  const GoalTracker* t = fleet.tracker("a");
  ASSERT_TRUE(t->has_frontier());
  // Off into new ground, its uncertainty grows: below the limit it explores on.
  fleet.observe_uncertainty("a", 0.09);
  fleet.observe("a", {1.55, 0.25});
  fleet.tick(g, kSecond);
  EXPECT_TRUE(t->has_frontier());
  fleet.observe_uncertainty("a", 0.14);
  fleet.observe("a", {1.85, 0.25});
  fleet.tick(g, 2 * kSecond);
  ASSERT_TRUE(t->revisiting());
  EXPECT_EQ(t->plan_target(), (Vec2{0.55, 0.25}));
  EXPECT_FALSE(t->waypoints().empty());
  std::vector<Revisit> revisits;
  fleet.take_revisits(revisits);
  ASSERT_EQ(revisits.size(), 1u);
  EXPECT_EQ(revisits[0].robot_id, "a");
  EXPECT_DOUBLE_EQ(revisits[0].sigma_m, 0.14);
  // Tied again on the way back: it explores on from there.
  fleet.observe("a", {1.25, 0.25});
  fleet.observe_uncertainty("a", 0.05);
  fleet.tick(g, 3 * kSecond);
  EXPECT_FALSE(t->revisiting());
  EXPECT_TRUE(t->has_frontier());
  fleet.take_revisits(revisits);
  EXPECT_EQ(revisits.size(), 1u);  // no other
}

TEST(FleetExplore, ARobotThatDoesNotTieWhereItWentBackExploresOnAnyway) {
  const PlanningGrid g = strip();
  Fleet fleet({});
  fleet.observe("a", {0.55, 0.25});
  fleet.observe_uncertainty("a", 0.08);
  fleet.observe_uncertainty("a", 0.04);
  fleet.grid_changed(g, std::nullopt);
  ASSERT_TRUE(fleet.set_goal("a", explore_goal()));
  fleet.tick(g, 0);
  fleet.observe_uncertainty("a", 0.2);
  fleet.observe("a", {1.85, 0.25});
  fleet.tick(g, kSecond);
  const GoalTracker* t = fleet.tracker("a");
  ASSERT_TRUE(t->revisiting());
  fleet.observe("a", {0.55, 0.25});  // arrived, still uncertain
  fleet.tick(g, 2 * kSecond);
  EXPECT_FALSE(t->revisiting());
  EXPECT_TRUE(t->has_frontier());
  fleet.observe("a", {1.0, 0.25});
  fleet.tick(g, 3 * kSecond);
  EXPECT_TRUE(t->has_frontier());  // not sent back a second time
}

TEST(FleetExplore, ARobotWithNothingObservedAroundItWaitsForTheMap) {
  PlanningGrid g = test::uniform_grid(40, 20, kCellUnknown, kRes);
  for (int32_t y = 5; y < 15; ++y) {
    for (int32_t x = 25; x < 35; ++x) g.set({x, y}, kCellFree);
  }
  Fleet fleet({});
  fleet.observe("a", {0.55, 1.05});
  fleet.grid_changed(g, std::nullopt);
  ASSERT_TRUE(fleet.set_goal("a", explore_goal()));
  for (int64_t now = 0; now <= 10 * kSecond; now += kSecond / 2) fleet.tick(g, now);
  const GoalTracker* t = fleet.tracker("a");
  EXPECT_EQ(t->status(), GoalStatus::Active);
  EXPECT_TRUE(t->wants_frontier());
  EXPECT_FALSE(t->homing());
  EXPECT_FALSE(fleet.exploration_complete());
  // Its first scan arrives: the free patch now reaches the robot.
  for (int32_t y = 5; y < 15; ++y) {
    for (int32_t x = 3; x < 25; ++x) g.set({x, y}, kCellFree);
  }
  fleet.grid_changed(g, std::nullopt);
  fleet.tick(g, 11 * kSecond);
  EXPECT_TRUE(t->has_frontier());
}

TEST(FleetExplore, NothingLeftMeansHomeOnlyAfterTheGracePeriod) {
  const PlanningGrid room = test::grid_from_art(
      {
          "##########",
          "#........#",
          "#........#",
          "#........#",
          "##########",
      },
      kRes);
  FleetConfig config;
  config.explore.completion_grace_s = 3.0;
  Fleet fleet(config);
  fleet.observe("a", {0.45, 0.25});
  fleet.grid_changed(room, std::nullopt);
  ASSERT_TRUE(fleet.set_goal("a", explore_goal()));
  int64_t now = 0;
  for (; now < 3 * kSecond; now += kSecond / 2) {
    fleet.tick(room, now);
    EXPECT_FALSE(fleet.tracker("a")->homing()) << "at " << now / kSecond << " s";
  }
  for (; now <= 4 * kSecond; now += kSecond / 2) fleet.tick(room, now);
  EXPECT_TRUE(fleet.tracker("a")->homing());
  EXPECT_TRUE(fleet.exploration_complete());
}

TEST(FleetExplore, AnIdleRobotWaitsWhileAnotherStillExplores) {
  const PlanningGrid g = strip();
  Fleet fleet({});  // one frontier cluster, two robots
  fleet.observe("a", {0.55, 0.25});
  fleet.observe("b", {1.55, 0.25});
  fleet.grid_changed(g, std::nullopt);
  ASSERT_TRUE(fleet.set_goal(kAllRobots, explore_goal()));
  for (int64_t now = 0; now <= 10 * kSecond; now += kSecond / 2) fleet.tick(g, now);
  const GoalTracker* a = fleet.tracker("a");
  const GoalTracker* b = fleet.tracker("b");
  ASSERT_NE(a->has_frontier(), b->has_frontier()) << "one cluster: exactly one robot goes";
  EXPECT_FALSE(a->homing());
  EXPECT_FALSE(b->homing());
  EXPECT_FALSE(fleet.exploration_complete());
}

TEST(FleetExplore, AFrontierStillThereWhenReachedIsNotHandedOutAgain) {
  const PlanningGrid g = strip();
  Fleet fleet({});
  fleet.observe("a", {0.55, 0.25});
  fleet.grid_changed(g, std::nullopt);
  ASSERT_TRUE(fleet.set_goal("a", explore_goal()));
  fleet.tick(g, 0);
  const GoalTracker* t = fleet.tracker("a");
  ASSERT_TRUE(t->has_frontier());
  const Vec2 target = t->plan_target();
  fleet.observe("a", target);  // arrived; the map does not change (nothing visible from there)
  fleet.tick(g, kSecond);
  EXPECT_EQ(fleet.blacklist().size(), 1u);
  EXPECT_TRUE(fleet.blacklist().contains(target, 1e-9, kSecond));
  EXPECT_FALSE(t->has_frontier() && distance(t->plan_target(), target) < 0.5);
}

TEST(FleetExplore, ARestingFrontierKeepsExplorationOpenUntilItIsGivenUpForGood) {
  // The only frontier was reached without uncovering anything: it rests (30 s), so the robot
  // waits instead of calling the exploration done, tries it once more, and only then goes home.
  const PlanningGrid g = strip();
  FleetConfig config;
  config.explore.completion_grace_s = 3.0;
  config.explore.blacklist_rest_s = 30.0;
  Fleet fleet(config);
  fleet.observe("a", {0.55, 0.25});
  fleet.grid_changed(g, std::nullopt);
  ASSERT_TRUE(fleet.set_goal("a", explore_goal()));
  fleet.tick(g, 0);
  const GoalTracker* t = fleet.tracker("a");
  ASSERT_TRUE(t->has_frontier());
  const Vec2 target = t->plan_target();
  fleet.observe("a", target);
  int64_t now = kSecond;
  for (; now < 30 * kSecond; now += kSecond / 2) {
    fleet.tick(g, now);
    ASSERT_FALSE(t->homing()) << "went home at " << now / kSecond << " s while the frontier rests";
  }
  EXPECT_FALSE(fleet.exploration_complete());
  // The rest is over: the robot, still standing on it, is given it again, reaches it at once
  // and, nothing new seen, it is given up for good (a second blacklist entry).
  for (; now <= 33 * kSecond && fleet.blacklist().size() < 2; now += kSecond / 2) fleet.tick(g, now);
  ASSERT_EQ(fleet.blacklist().size(), 2u) << "the rested frontier was not offered again";
  EXPECT_FALSE(fleet.blacklist().rests(target, 0.5, now));
  for (const int64_t end = now + 5 * kSecond; now <= end; now += kSecond / 2) fleet.tick(g, now);
  EXPECT_TRUE(t->homing());
  EXPECT_TRUE(fleet.exploration_complete());
}

TEST(FleetExplore, AWalledInStartDoesNotBlacklistTheFrontier) {
  PlanningGrid g = strip();
  Fleet fleet({});
  const Vec2 start{1.05, 0.25};
  fleet.observe("a", start);
  fleet.grid_changed(g, std::nullopt);
  ASSERT_TRUE(fleet.set_goal("a", explore_goal()));
  fleet.tick(g, 0);
  ASSERT_TRUE(fleet.tracker("a")->has_frontier());
  // Walls close around the robot (a map error, or a robot boxed in); its cell is inflated then.
  const Cell c = *g.cell_at(start);
  for (int32_t dy = -1; dy <= 1; ++dy) {
    for (int32_t dx = -1; dx <= 1; ++dx) g.set({c.x + dx, c.y + dy}, kCellOccupied);
  }
  g.set(c, kCellFree | kCellInflated);
  fleet.grid_changed(g, std::nullopt);
  for (int64_t now = kSecond; now <= 10 * kSecond; now += kSecond / 2) fleet.tick(g, now);
  const GoalTracker* t = fleet.tracker("a");
  EXPECT_EQ(fleet.blacklist().size(), 0u);
  EXPECT_FALSE(t->has_frontier());
  EXPECT_EQ(t->status(), GoalStatus::Active);  // waiting, neither failed nor done
  EXPECT_FALSE(t->homing());
}

}  // namespace
}  // namespace slam::planner
