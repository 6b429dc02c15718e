// PathPlanner: request checks and statuses, A* and each OMPL planner on a small map.
#include "planner/core/path_planner.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "grid_builder.hpp"
#include "planner/core/line_of_sight.hpp"

namespace slam::planner {
namespace {

// 0.1 m cells; two walls with doors on opposite sides force an S-shaped route.
PlanningGrid two_rooms() {
  PlanningGrid g = test::uniform_grid(60, 40, kCellFree, 0.1);
  for (int y = 0; y < 40; ++y) {
    if (y < 30) g.set({20, y}, kCellOccupied);
    if (y >= 10) g.set({40, y}, kCellOccupied);
  }
  return g;
}

void expect_clear(const PlanningGrid& g, const PlanResult& r) {
  ASSERT_GE(r.path.size(), 2u);
  for (size_t i = 1; i < r.path.size(); ++i) {
    EXPECT_TRUE(segment_clear(g, r.path[i - 1], r.path[i], UnknownPolicy::Blocked)) << "segment " << i;
  }
  EXPECT_NEAR(r.length_m, path_length(r.path), 1e-9);
}

TEST(PathPlanner, AstarPlansAroundWalls) {
  const PlanningGrid g = two_rooms();
  PathPlanner p({});
  const PlanResult r = p.plan(g, {{0.5, 0.5}, {5.5, 3.5}, "astar", 1.0});
  ASSERT_EQ(r.status, PlanStatus::Ok) << r.reason;
  EXPECT_TRUE(r.reason.empty());
  EXPECT_EQ(r.path.front(), (Vec2{0.5, 0.5}));
  EXPECT_EQ(r.path.back(), (Vec2{5.5, 3.5}));
  EXPECT_LE(r.path.size(), 6u);
  expect_clear(g, r);
}

TEST(PathPlanner, OmplPlannersFindClearPaths) {
  const PlanningGrid g = two_rooms();
  PathPlanner p({});
  const double astar_length = p.plan(g, {{0.5, 0.5}, {5.5, 3.5}, "astar", 1.0}).length_m;
  // fmtstar: FmtStarPathsAreWithinATenthOfAstar.
  for (const char* algorithm : {"rrtconnect", "rrtstar", "prmstar"}) {
    const PlanResult r = p.plan(g, {{0.5, 0.5}, {5.5, 3.5}, algorithm, 0.3});
    ASSERT_EQ(r.status, PlanStatus::Ok) << algorithm << ": " << r.reason;
    EXPECT_NEAR(r.path.front().x, 0.5, 1e-9);
    EXPECT_NEAR(r.path.back().y, 3.5, 1e-6);
    expect_clear(g, r);
    EXPECT_GE(r.length_m, astar_length * 0.9) << algorithm;
    EXPECT_GT(r.planning_time_s, 0.0);
  }
}

// FMT* samples a fixed number of states with OMPL's generator, seeded once per process
// (PlannerConfig::ompl_seed): on this small map its 8000 states leave no room for a detour. It
// stops when it reaches the goal: the generous budget only keeps a loaded machine from cutting it.
TEST(PathPlanner, FmtStarPathsAreWithinATenthOfAstar) {
  const PlanningGrid g = two_rooms();
  PathPlanner p({});
  const double astar_length = p.plan(g, {{0.5, 0.5}, {5.5, 3.5}, "astar", 1.0}).length_m;
  for (int run = 0; run < 5; ++run) {
    const PlanResult r = p.plan(g, {{0.5, 0.5}, {5.5, 3.5}, "fmtstar", 10.0});
    ASSERT_EQ(r.status, PlanStatus::Ok) << r.reason;
    expect_clear(g, r);
    EXPECT_LE(r.length_m, 1.10 * astar_length) << "run " << run;
  }
}

TEST(PathPlanner, RobotGoalsCanBePlannedWithASamplingPlanner) {
  const PlanningGrid g = two_rooms();
  PlannerConfig config;
  config.goal_time_budget_s = 10.0;  // FMT* stops at the goal; A* would take over after the budget
  PathPlanner p(config);
  const PlanResult r = p.plan_for_robot(g, {0.5, 0.5}, {5.5, 3.5}, UnknownPolicy::Allowed, false, "fmtstar");
  ASSERT_EQ(r.status, PlanStatus::Ok) << r.reason;
  expect_clear(g, r);
  EXPECT_EQ(r.path.back(), (Vec2{5.5, 3.5}));
  // Enclosed stays enclosed whatever the algorithm (FMT* samples on until its default budget).
  PlanningGrid closed = test::uniform_grid(30, 10, kCellFree, 0.1);
  for (int y = 0; y < 10; ++y) closed.set({15, y}, kCellOccupied);
  PathPlanner q({});
  const PlanResult none =
      q.plan_for_robot(closed, {0.5, 0.5}, {2.5, 0.5}, UnknownPolicy::Allowed, false, "fmtstar");
  EXPECT_EQ(none.status, PlanStatus::NoPath) << none.reason;
}

TEST(PathPlanner, RejectsBadRequestsWithReasons) {
  const PlanningGrid g = two_rooms();
  PathPlanner p({});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  struct Case {
    PathQuery q;
    PlanStatus want;
    const char* words;
  };
  const Case cases[] = {
      {{{nan, 0.5}, {1, 1}, "astar", 1.0}, PlanStatus::InvalidRequest, "start is not finite"},
      {{{0.5, 0.5}, {1, inf}, "astar", 1.0}, PlanStatus::InvalidRequest, "goal is not finite"},
      {{{0.5, 0.5}, {1, 1}, "dijkstra", 1.0}, PlanStatus::InvalidRequest, "unknown algorithm"},
      {{{0.5, 0.5}, {1, 1}, "rrtconnect", 0.0}, PlanStatus::InvalidRequest, "time budget"},
      {{{0.5, 0.5}, {1, 1}, "rrtconnect", nan}, PlanStatus::InvalidRequest, "time budget"},
      {{{0.5, 0.5}, {1, 1}, "astar", 1e9}, PlanStatus::InvalidRequest, "exceeds"},
      {{{-0.5, 0.5}, {1, 1}, "astar", 1.0}, PlanStatus::InvalidRequest, "outside the map"},
      {{{0.5, 0.5}, {6.5, 1}, "astar", 1.0}, PlanStatus::InvalidRequest, "outside the map"},
      {{{2.05, 0.5}, {1, 1}, "astar", 1.0}, PlanStatus::StartBlocked, "obstacle"},
      {{{0.5, 0.5}, {4.05, 2.0}, "prmstar", 1.0}, PlanStatus::GoalBlocked, "obstacle"},
  };
  for (const Case& c : cases) {
    const PlanResult r = p.plan(g, c.q);
    EXPECT_EQ(r.status, c.want) << c.words;
    EXPECT_NE(r.reason.find(c.words), std::string::npos) << r.reason;
    EXPECT_TRUE(r.path.empty());
  }
  EXPECT_EQ(p.plan(PlanningGrid{}, {{0, 0}, {1, 1}, "astar", 1.0}).status, PlanStatus::NoMap);
}

TEST(PathPlanner, ReportsNoPathForEveryAlgorithm) {
  PlanningGrid g = test::uniform_grid(30, 10, kCellFree, 0.1);
  for (int y = 0; y < 10; ++y) g.set({15, y}, kCellOccupied | kCellObstructed);
  PathPlanner p({});
  for (const char* algorithm : {"astar", "rrtconnect"}) {
    const PlanResult r = p.plan(g, {{0.5, 0.5}, {2.5, 0.5}, algorithm, 0.05});
    EXPECT_EQ(r.status, PlanStatus::NoPath) << algorithm;
    EXPECT_NE(r.reason.find("no path"), std::string::npos);
  }
}

TEST(PathPlanner, UnknownPolicyComesFromConfig) {
  const PlanningGrid g = test::grid_from_art({"..??.."}, 1.0);
  PlannerConfig strict_config;
  strict_config.unknown = UnknownPolicy::Blocked;
  PathPlanner strict(strict_config);
  EXPECT_EQ(strict.plan(g, {{0.5, 0.5}, {5.5, 0.5}, "astar", 1.0}).status, PlanStatus::NoPath);
  EXPECT_EQ(strict.plan(g, {{0.5, 0.5}, {2.5, 0.5}, "astar", 1.0}).status, PlanStatus::GoalBlocked);
  PathPlanner lenient({});  // the default (unknown_space_test.cpp)
  EXPECT_EQ(lenient.plan(g, {{0.5, 0.5}, {5.5, 0.5}, "astar", 1.0}).status, PlanStatus::Ok);
}

TEST(PathPlanner, ValidatesConfig) {
  PlannerConfig c;
  EXPECT_TRUE(validate(c));
  c.unknown_cost_factor = 0.5;
  EXPECT_FALSE(validate(c));
  c = {};
  c.max_time_budget_s = 0.0;
  EXPECT_FALSE(validate(c));
  c = {};
  c.ompl_range_m = -1.0;
  EXPECT_FALSE(validate(c));
  c.ompl_range_m = 0.0;  // OMPL's own default
  EXPECT_TRUE(validate(c));
  c = {};
  c.goal_algorithm = "dijkstra";
  EXPECT_FALSE(validate(c));
  c.goal_algorithm = "fmtstar";
  EXPECT_TRUE(validate(c));
  c.goal_time_budget_s = 0.0;
  EXPECT_FALSE(validate(c));
  c = {};
  c.ompl_fmt_samples = 10;
  EXPECT_FALSE(validate(c));
}

}  // namespace
}  // namespace slam::planner
