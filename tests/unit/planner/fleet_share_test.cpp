// Fleet shared by several planners: only owned robots are planned, explored and streamed; a robot
// taken over continues its goal at once; frontiers claimed by other planners' robots are not
// offered here.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "grid_builder.hpp"
#include "planner/core/fleet.hpp"

namespace slam::planner {
namespace {

constexpr int64_t kSecond = 1'000'000'000;
constexpr double kRes = 0.1;

std::vector<std::string> due_robots(Fleet& fleet, int64_t now_ns) {
  std::vector<DueWaypoint> due;
  fleet.due_waypoints(now_ns, due);
  std::vector<std::string> ids;
  for (const DueWaypoint& d : due) ids.push_back(d.robot_id);
  return ids;
}

// A room known inside, unexplored beyond its left and right openings: two frontier clusters.
PlanningGrid two_openings() {
  return test::grid_from_art(
      {
          "####################",
          "?..................?",
          "?..................?",
          "?..................?",
          "?..................?",
          "?..................?",
          "####################",
      },
      kRes);
}

TEST(FleetShare, OnlyOwnedRobotsGetWaypointsAndPaths) {
  Fleet fleet({});
  fleet.observe("a", {0, 0});
  fleet.observe("b", {1, 0});
  ASSERT_TRUE(fleet.set_goal(kAllRobots, Goal{1, GoalMode::Direct, {5, 0}, 0, {}}));
  EXPECT_EQ(fleet.update_ownership([](const std::string& id) { return id == "a"; }), 1u);
  EXPECT_TRUE(fleet.owns("a"));
  EXPECT_FALSE(fleet.owns("b"));
  EXPECT_FALSE(fleet.owns("unknown"));
  EXPECT_EQ(due_robots(fleet, 0), std::vector<std::string>{"a"});
  EXPECT_EQ(fleet.take_changed(), std::vector<std::string>{"a"});
  // Every goal is still followed for every robot: b's goal is known here.
  EXPECT_EQ(fleet.tracker("b")->goal().goal_id, 1u);
  EXPECT_EQ(fleet.tracker("b")->status(), GoalStatus::Active);
}

TEST(FleetShare, ARobotTakenOverContinuesWhereItIs) {
  Fleet fleet({});
  fleet.observe("b", {0, 0});
  ASSERT_TRUE(fleet.set_goal("b", Goal{2, GoalMode::Square, {0, 0}, 2.0, SquareAnchor::Corner}));
  fleet.update_ownership([](const std::string&) { return false; });
  EXPECT_TRUE(fleet.take_changed().empty());
  // Driven by its owner elsewhere: this planner follows its progress along the square.
  fleet.observe("b", {2, 0});
  const auto before = fleet.tracker("b")->current_index();
  EXPECT_TRUE(due_robots(fleet, kSecond).empty());
  // Its owner died: the next waypoint goes out at once, and its path is published.
  EXPECT_EQ(fleet.update_ownership([](const std::string&) { return true; }), 1u);
  std::vector<DueWaypoint> due;
  fleet.due_waypoints(kSecond, due);
  ASSERT_EQ(due.size(), 1u);
  EXPECT_EQ(fleet.tracker("b")->current_index(), before);
  EXPECT_EQ(due[0].waypoint, (Vec2{2, 2}));
  EXPECT_EQ(fleet.take_changed(), std::vector<std::string>{"b"});
}

TEST(FleetShare, APlannedGoalTakenOverIsPlannedFromTheRobotsPosition) {
  const PlanningGrid g = test::grid_from_art({
      ".........",
      ".........",
      ".........",
  });
  Fleet fleet({});
  fleet.observe("a", {0.5, 0.5});
  ASSERT_TRUE(fleet.set_goal("a", Goal{3, GoalMode::Planned, {8.5, 2.5}, 0, {}}));
  fleet.update_ownership([](const std::string&) { return false; });
  fleet.grid_changed(g, std::nullopt);
  fleet.tick(g, 0);
  EXPECT_TRUE(fleet.tracker("a")->waypoints().empty()) << "not owned: never planned here";
  fleet.observe("a", {4.5, 1.5});
  fleet.update_ownership([](const std::string&) { return true; });
  fleet.tick(g, kSecond);
  const GoalTracker* t = fleet.tracker("a");
  ASSERT_FALSE(t->waypoints().empty());
  EXPECT_EQ(t->waypoints().back(), (Vec2{8.5, 2.5}));
  EXPECT_EQ(due_robots(fleet, kSecond), std::vector<std::string>{"a"});
}

TEST(FleetShare, AFrontierClaimedByAnotherPlannersRobotIsNotOfferedHere) {
  const PlanningGrid g = two_openings();
  const Vec2 start{0.45, 0.35};  // nearer the left opening
  const auto explore_from = [&](Fleet& fleet) {
    fleet.observe("a", start);
    fleet.grid_changed(g, std::nullopt);
    EXPECT_TRUE(fleet.set_goal("a", Goal{1, GoalMode::Explore, {}, 0, {}}));
    fleet.tick(g, 0);
    EXPECT_TRUE(fleet.tracker("a")->has_frontier());
    return fleet.tracker("a")->plan_target();
  };
  Fleet alone({});
  EXPECT_LT(explore_from(alone).x, 1.0);

  Fleet shared({});
  shared.claim("x", Vec2{0.15, 0.35});  // robot x of another planner drives to the left opening
  EXPECT_GT(explore_from(shared).x, 1.0);

  // A claim for a robot owned here is stale (its old owner's): it takes nothing.
  Fleet stale({});
  stale.observe("x", {1.0, 0.35});
  stale.claim("x", Vec2{0.15, 0.35});
  EXPECT_LT(explore_from(stale).x, 1.0);
}

TEST(FleetShare, ARobotGivenUpDropsItsFrontierForItsNewOwnerToChoose) {
  const PlanningGrid g = two_openings();
  Fleet fleet({});
  fleet.observe("a", {0.45, 0.35});
  fleet.grid_changed(g, std::nullopt);
  ASSERT_TRUE(fleet.set_goal("a", Goal{1, GoalMode::Explore, {}, 0, {}}));
  fleet.tick(g, 0);
  ASSERT_TRUE(fleet.tracker("a")->has_frontier());
  fleet.update_ownership([](const std::string&) { return false; });
  EXPECT_FALSE(fleet.tracker("a")->has_frontier());
  fleet.tick(g, kSecond);
  EXPECT_FALSE(fleet.tracker("a")->has_frontier()) << "not owned: no frontier chosen here";
  EXPECT_FALSE(fleet.exploration_complete());
  // Back to this planner: it explores again.
  fleet.update_ownership([](const std::string&) { return true; });
  fleet.tick(g, 2 * kSecond);
  EXPECT_TRUE(fleet.tracker("a")->has_frontier());
}

}  // namespace
}  // namespace slam::planner
