// Fleet: goal fan-out, waypoint streaming, and a whole exploration run on a hidden world where
// simulated robots reveal what they can see and drive to the waypoints they are given.
#include "planner/core/fleet.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "grid_builder.hpp"
#include "hidden_world.hpp"

namespace slam::planner {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

TEST(Fleet, GoalsForAllRobotsReachEachKnownRobot) {
  Fleet fleet({});
  fleet.observe("a", {0, 0});
  fleet.observe("b", {1, 1});
  ASSERT_TRUE(fleet.set_goal(kAllRobots, Goal{7, GoalMode::Direct, {5, 5}, 0, {}}));
  EXPECT_EQ(fleet.tracker("a")->goal().goal_id, 7u);
  EXPECT_EQ(fleet.tracker("b")->mode(), GoalMode::Direct);
  // Not seen yet: kept for later, started for nobody now.
  const auto kept = fleet.set_goal("c", Goal{8, GoalMode::Stop, {}, 0, {}});
  ASSERT_TRUE(kept);
  EXPECT_EQ(*kept, 0u);
  ASSERT_NE(fleet.pending_goal("c"), nullptr);
  EXPECT_EQ(fleet.tracker("c"), nullptr);
  EXPECT_FALSE(fleet.set_goal("a", Goal{9, GoalMode::Square, {}, -1.0, {}}));

  std::vector<DueWaypoint> due;
  fleet.due_waypoints(0, due);
  ASSERT_EQ(due.size(), 2u);
  EXPECT_EQ(due[0].waypoint, (Vec2{5, 5}));
  fleet.due_waypoints(kSecond / 2, due);
  EXPECT_TRUE(due.empty());
  fleet.due_waypoints(kSecond, due);
  EXPECT_EQ(due.size(), 2u);
  EXPECT_EQ(fleet.take_changed().size(), 2u);
  EXPECT_TRUE(fleet.take_changed().empty());
}

TEST(Fleet, AGoalForARobotNotSeenYetStartsOnItsFirstPosition) {
  Fleet fleet({});
  ASSERT_EQ(*fleet.set_goal("late", Goal{3, GoalMode::Direct, {4, 0}, 0, {}}), 0u);
  fleet.observe("late", {0, 0});
  const GoalTracker* t = fleet.tracker("late");
  ASSERT_NE(t, nullptr);
  EXPECT_EQ(t->goal().goal_id, 3u);
  EXPECT_EQ(t->status(), GoalStatus::Active);
  EXPECT_EQ(t->current_waypoint(), (Vec2{4, 0}));
  EXPECT_EQ(fleet.pending_goal("late"), nullptr);
  EXPECT_EQ(fleet.take_changed(), std::vector<std::string>{"late"});
}

TEST(Fleet, FleetWideExploreAndStopGoalsReachRobotsThatAppearLater) {
  Fleet fleet({});
  ASSERT_EQ(*fleet.set_goal(kAllRobots, Goal{5, GoalMode::Explore, {}, 0, {}}), 0u);
  fleet.observe("a", {0, 0});
  EXPECT_EQ(fleet.tracker("a")->mode(), GoalMode::Explore);
  EXPECT_EQ(fleet.tracker("a")->goal().goal_id, 5u);
  // A robot's own goal wins when it came later, the fleet goal when it did.
  ASSERT_EQ(*fleet.set_goal("b", Goal{6, GoalMode::Stop, {}, 0, {}}), 0u);
  fleet.observe("b", {1, 0});
  EXPECT_EQ(fleet.tracker("b")->goal().goal_id, 6u);
  ASSERT_EQ(*fleet.set_goal("c", Goal{7, GoalMode::Home, {}, 0, {}}), 0u);
  ASSERT_EQ(*fleet.set_goal(kAllRobots, Goal{8, GoalMode::Stop, {}, 0, {}}), 2u);
  EXPECT_NE(fleet.pending_goal("c"), nullptr);  // kept, but the later fleet goal wins
  fleet.observe("c", {2, 0});
  EXPECT_EQ(fleet.pending_goal("c"), nullptr);
  EXPECT_EQ(fleet.tracker("c")->goal().goal_id, 8u);
  EXPECT_EQ(fleet.tracker("c")->mode(), GoalMode::Stop);
  // A target chosen for the robots there does not stand for newcomers.
  ASSERT_EQ(*fleet.set_goal(kAllRobots, Goal{9, GoalMode::Direct, {5, 5}, 0, {}}), 3u);
  fleet.observe("d", {3, 0});
  EXPECT_EQ(fleet.tracker("d")->status(), GoalStatus::None);
}

TEST(Fleet, GoalsWaitingForUnseenRobotsAreBounded) {
  Fleet fleet({});
  for (size_t i = 0; i < Fleet::kMaxPendingGoals; ++i) {
    ASSERT_TRUE(fleet.set_goal("ghost-" + std::to_string(i), Goal{1, GoalMode::Stop, {}, 0, {}}));
  }
  const auto refused = fleet.set_goal("one-more", Goal{1, GoalMode::Stop, {}, 0, {}});
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.message().find("unknown robot 'one-more'"), std::string::npos);
  // Replacing a kept goal is fine.
  EXPECT_TRUE(fleet.set_goal("ghost-0", Goal{2, GoalMode::Stop, {}, 0, {}}));
}

TEST(Fleet, PlansAndReportsFailures) {
  const PlanningGrid g = test::grid_from_art({
      "....#....",
      "....#....",
      "....#....",
  });
  Fleet fleet({});
  fleet.observe("a", {0.5, 0.5});
  ASSERT_TRUE(fleet.set_goal("a", Goal{1, GoalMode::Planned, {8.5, 2.5}, 0, {}}));
  fleet.grid_changed(g, std::nullopt);
  fleet.tick(g, 0);
  EXPECT_EQ(fleet.tracker("a")->status(), GoalStatus::Failed);
  EXPECT_NE(fleet.tracker("a")->reason().find("NO_PATH"), std::string::npos);
  ASSERT_TRUE(fleet.set_goal("a", Goal{2, GoalMode::Planned, {3.5, 2.5}, 0, {}}));
  fleet.tick(g, 0);
  EXPECT_EQ(fleet.tracker("a")->status(), GoalStatus::Active);
  EXPECT_EQ(fleet.tracker("a")->waypoints().back(), (Vec2{3.5, 2.5}));
}

// The world the exploration test's robots uncover.
const std::vector<std::string> kExploredWorld = {
    "##############################", "#............#...............#", "#............#...............#",
    "#............#.......#.......#", "#....................#.......#", "#............#.......#.......#",
    "######.#######.......#########", "#............#...............#", "#............#...............#",
    "#............................#", "#............#...............#", "##############################",
};

TEST(Fleet, ExploresTheWholeWorldAndComesHome) {
  test::HiddenWorld world(kExploredWorld);
  FleetConfig config;
  config.explore.min_cluster_cells = 2;
  config.goals.reach_tolerance_m = 0.3;
  Fleet fleet(config);
  const std::vector<std::pair<std::string, Vec2>> start{{"r1", {2.5, 2.5}}, {"r2", {3.5, 2.5}}};
  std::map<std::string, Vec2> pos;
  for (const auto& [id, p] : start) {
    pos[id] = p;
    world.sense(p);
    fleet.observe(id, p);
  }
  fleet.grid_changed(world.map(), std::nullopt);
  ASSERT_TRUE(fleet.set_goal(kAllRobots, Goal{1, GoalMode::Explore, {}, 0, {}}));
  int64_t now = 0;
  bool done = false;
  for (int step = 0; step < 400 && !done; ++step, now += kSecond / 2) {
    fleet.tick(world.map(), now);
    // Never two robots chasing the same frontier.
    const GoalTracker* t1 = fleet.tracker("r1");
    const GoalTracker* t2 = fleet.tracker("r2");
    if (t1->has_frontier() && t2->has_frontier()) {
      EXPECT_NE(t1->plan_target(), t2->plan_target());
    }
    for (auto& [id, p] : pos) {
      const auto wp = fleet.tracker(id)->current_waypoint();
      if (fleet.tracker(id)->status() != GoalStatus::Active || !wp) continue;
      // Drive up to 1 m toward the waypoint.
      const double d = distance(p, *wp);
      const double s = std::min(1.0, d) / std::max(d, 1e-9);
      p = Vec2{p.x + (wp->x - p.x) * s, p.y + (wp->y - p.y) * s};
      const CellBox sensed = world.sense(p);
      fleet.grid_changed(world.map(), std::span<const CellBox>(&sensed, 1));
      fleet.observe(id, p);
    }
    done = fleet.tracker("r1")->status() == GoalStatus::Reached &&
           fleet.tracker("r2")->status() == GoalStatus::Reached;
  }
  ASSERT_TRUE(done);
  EXPECT_TRUE(fleet.exploration_complete());
  for (const auto& [id, p] : start) {
    EXPECT_TRUE(fleet.tracker(id)->homing());
    EXPECT_LE(distance(pos[id], p), config.goals.reach_tolerance_m);
  }
  // Every free cell reachable from the start is now known.
  FrontierMap f;
  f.rebuild(world.map());
  std::vector<FrontierCluster> left;
  f.cluster(world.map(), 2, left);
  EXPECT_TRUE(left.empty());
  int unknown_inside = 0;
  for (int32_t y = 1; y < 11; ++y) {
    for (int32_t x = 1; x < 29; ++x) unknown_inside += world.map().unknown({x, y}) ? 1 : 0;
  }
  EXPECT_LT(unknown_inside, 10);
}

}  // namespace
}  // namespace slam::planner
