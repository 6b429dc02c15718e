// Targets in unexplored space: path requests and robot goals plan through unknown cells by default,
// re-plan as the map fills in, and fail only when the target is enclosed by known walls or in an
// obstacle; the blocked policy still refuses them.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "grid_builder.hpp"
#include "hidden_world.hpp"
#include "planner/core/fleet.hpp"
#include "planner/core/line_of_sight.hpp"
#include "planner/core/path_planner.hpp"

namespace slam::planner {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

bool contains(const std::string& text, const std::string& words) {
  return text.find(words) != std::string::npos;
}

// A known room (x 4..8, y 1..4) around an unexplored inside, in unexplored surroundings.
PlanningGrid closed_room() {
  return test::grid_from_art({
      "??????????",
      "...#####??",
      "...#???#??",
      "...#???#??",
      "...#####??",
      "..........",
  });
}

TEST(PathPlanner, PlansThroughUnexploredSpaceByDefault) {
  const PlanningGrid g = test::grid_from_art({"..??.."}, 1.0);
  PathPlanner p({});
  EXPECT_EQ(p.config().unknown, UnknownPolicy::Allowed);
  for (const char* algorithm : {"astar", "rrtconnect"}) {
    const PlanResult across = p.plan(g, {{0.5, 0.5}, {5.5, 0.5}, algorithm, 0.5});
    EXPECT_EQ(across.status, PlanStatus::Ok) << algorithm << ": " << across.reason;
    const PlanResult into = p.plan(g, {{0.5, 0.5}, {2.5, 0.5}, algorithm, 0.5});
    EXPECT_EQ(into.status, PlanStatus::Ok) << algorithm << ": " << into.reason;
  }
  const PlanResult robot = p.plan_for_robot(g, {0.5, 0.5}, {3.5, 0.5}, UnknownPolicy::Allowed);
  ASSERT_EQ(robot.status, PlanStatus::Ok) << robot.reason;
  EXPECT_EQ(robot.path.back(), (Vec2{3.5, 0.5}));
}

TEST(PathPlanner, TheBlockedPolicyStillRefusesUnexploredSpaceAndSaysSo) {
  const PlanningGrid g = test::grid_from_art({"..??.."}, 1.0);
  PlannerConfig config;
  config.unknown = UnknownPolicy::Blocked;
  PathPlanner p(config);
  const PlanResult across = p.plan(g, {{0.5, 0.5}, {5.5, 0.5}, "astar", 1.0});
  EXPECT_EQ(across.status, PlanStatus::NoPath);
  EXPECT_TRUE(contains(across.reason, "through explored space")) << across.reason;
  const PlanResult into = p.plan(g, {{0.5, 0.5}, {2.5, 0.5}, "astar", 1.0});
  EXPECT_EQ(into.status, PlanStatus::GoalBlocked);
  EXPECT_TRUE(contains(into.reason, "in unexplored space")) << into.reason;
}

TEST(PathPlanner, ATargetEnclosedByKnownWallsIsUnreachableForEveryAlgorithm) {
  const PlanningGrid g = closed_room();
  PathPlanner p({});
  for (const char* algorithm : {"astar", "rrtconnect", "prmstar"}) {
    const PlanResult r = p.plan(g, {{0.5, 0.5}, {5.5, 2.5}, algorithm, 0.05});
    EXPECT_EQ(r.status, PlanStatus::NoPath) << algorithm;
    EXPECT_TRUE(contains(r.reason, "enclosed by known walls")) << algorithm << ": " << r.reason;
  }
  const PlanResult robot = p.plan_for_robot(g, {0.5, 0.5}, {5.5, 2.5}, UnknownPolicy::Allowed);
  EXPECT_EQ(robot.status, PlanStatus::NoPath);
  EXPECT_TRUE(contains(robot.reason, "enclosed by known walls")) << robot.reason;
  // Outside the room the unexplored space is open.
  EXPECT_EQ(p.plan(g, {{0.5, 0.5}, {9.5, 5.5}, "astar", 1.0}).status, PlanStatus::Ok);
}

TEST(PathPlanner, ATargetInAnObstacleAmidUnexploredSpaceIsBlocked) {
  const PlanningGrid g = test::grid_from_art({"..?#?i?"}, 1.0);
  PathPlanner p({});
  for (const double x : {3.5, 5.5}) {
    const PlanResult r = p.plan(g, {{0.5, 0.5}, {x, 0.5}, "astar", 1.0});
    EXPECT_EQ(r.status, PlanStatus::GoalBlocked) << x;
    EXPECT_TRUE(contains(r.reason, "in an obstacle")) << r.reason;
  }
}

// A robot at `start` of `world` with a planned goal at `target`: drives up to 1 m a step toward its
// waypoint, sensing as it goes, until the goal is no longer active (or 200 steps). Every move must
// stay clear of the hidden walls.
struct Drive {
  Vec2 position;
  std::vector<Vec2> first_plan;
  GoalStatus status = GoalStatus::None;
  std::string reason;
};

Drive drive(test::HiddenWorld& world, Vec2 start, Vec2 target, const FleetConfig& config = {}) {
  Fleet fleet(config);
  Drive out{start, {}, {}, {}};
  world.sense(start);
  fleet.observe("r", start);
  fleet.grid_changed(world.map(), std::nullopt);
  EXPECT_TRUE(fleet.set_goal("r", Goal{1, GoalMode::Planned, target, 0, {}}));
  int64_t now = 0;
  for (int step = 0; step < 200; ++step, now += kSecond / 2) {
    fleet.tick(world.map(), now);
    const GoalTracker& t = *fleet.tracker("r");
    if (out.first_plan.empty()) out.first_plan.assign(t.waypoints().begin(), t.waypoints().end());
    const auto wp = t.current_waypoint();
    if (t.status() != GoalStatus::Active || !wp) break;
    const double d = distance(out.position, *wp);
    const double s = std::min(1.0, d) / std::max(d, 1e-9);
    const Vec2 next{out.position.x + (wp->x - out.position.x) * s,
                    out.position.y + (wp->y - out.position.y) * s};
    EXPECT_TRUE(segment_clear(world.truth(), out.position, next, UnknownPolicy::Blocked))
        << "drove into a wall at step " << step;
    out.position = next;
    const CellBox sensed = world.sense(out.position);
    fleet.grid_changed(world.map(), std::span<const CellBox>(&sensed, 1));
    fleet.observe("r", out.position);
  }
  out.status = fleet.tracker("r")->status();
  out.reason = fleet.tracker("r")->reason();
  return out;
}

TEST(Fleet, AGoalInUnexploredSpaceIsReachedByReplanningAsTheMapFillsIn) {
  // A wall the robot cannot see from its start stands between it and the target.
  test::HiddenWorld world({
      "####################",
      "#..................#",
      "#.........#........#",
      "#.........#........#",
      "#.........#........#",
      "#.........#........#",
      "#.........#........#",
      "#.........#........#",
      "#..................#",
      "####################",
  });
  const Vec2 start{2.5, 4.5};
  const Vec2 target{16.5, 4.5};
  const Drive d = drive(world, start, target);
  // The first plan went straight through the unseen wall: getting there took re-planning.
  ASSERT_FALSE(d.first_plan.empty());
  EXPECT_FALSE(segment_clear(world.truth(), start, d.first_plan.front(), UnknownPolicy::Blocked));
  EXPECT_EQ(d.status, GoalStatus::Reached) << d.reason;
  EXPECT_LE(distance(d.position, target), FleetConfig{}.goals.reach_tolerance_m);
}

TEST(Fleet, AGoalInUnexploredSpaceIsReachedWithASamplingGoalAlgorithmToo) {
  test::HiddenWorld world({
      "##############",
      "#............#",
      "#.....#......#",
      "#.....#......#",
      "#.....#......#",
      "#............#",
      "##############",
  });
  FleetConfig config;
  config.planner.goal_algorithm = "fmtstar";
  config.planner.ompl_fmt_samples = 500;
  const Vec2 target{11.5, 3.5};
  const Drive d = drive(world, {1.5, 3.5}, target, config);
  EXPECT_EQ(d.status, GoalStatus::Reached) << d.reason;
  EXPECT_LE(distance(d.position, target), config.goals.reach_tolerance_m);
}

TEST(Fleet, AGoalFoundEnclosedByWallsFailsWithTheReason) {
  test::HiddenWorld world({
      "####################",
      "#..................#",
      "#............#####.#",
      "#............#...#.#",
      "#............#...#.#",
      "#............#####.#",
      "#..................#",
      "#..................#",
      "#..................#",
      "####################",
  });
  const Drive d = drive(world, {2.5, 2.5}, {15.5, 5.5});
  EXPECT_EQ(d.status, GoalStatus::Failed);
  EXPECT_TRUE(contains(d.reason, "NO_PATH")) << d.reason;
  EXPECT_TRUE(contains(d.reason, "enclosed by known walls")) << d.reason;
}

}  // namespace
}  // namespace slam::planner
