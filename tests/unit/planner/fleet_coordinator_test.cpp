// Traffic rules: who goes, who waits, who steps aside, and deadlocks broken; checked on single
// decisions and on a small kinematic run (robots drive to their next waypoint or to where they are
// told to hold) that must end with every robot arrived and no two ever closer than two bodies.
#include "planner/core/fleet_coordinator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "grid_builder.hpp"
#include "planner/core/planner_options.hpp"
#include "traffic_run.hpp"

namespace slam::planner {
namespace {

using test::Bot;
using test::inputs;
using test::kArrive;
using test::kDt;
using test::kSpeed;
using test::run;
using test::RunResult;

// A 10 m x 10 m room at 0.1 m with a wall at x = 5 m and a 1 m door at y 4.5..5.5 m.
PlanningGrid door_room() {
  std::vector<std::string> rows(100, std::string(100, '.'));
  for (int r = 0; r < 100; ++r) {
    const double y = (99 - r + 0.5) * 0.1;
    if (y < 4.5 || y > 5.5) rows[static_cast<size_t>(r)][50] = '#';
  }
  return test::grid_from_art(rows, 0.1);
}

// A corridor 0.6 m wide along y = 5 m (x 0.5..9.5 m) with a niche going up at x niche_x0..niche_x1.
PlanningGrid corridor_with_niche(double niche_x0 = 5.0, double niche_x1 = 5.8) {
  std::vector<std::string> rows(100, std::string(100, '#'));
  for (int r = 0; r < 100; ++r) {
    const double y = (99 - r + 0.5) * 0.1;
    for (int c = 0; c < 100; ++c) {
      const double x = (c + 0.5) * 0.1;
      const bool corridor = y > 4.7 && y < 5.3 && x > 0.5 && x < 9.5;
      const bool niche = x > niche_x0 && x < niche_x1 && y >= 5.3 && y < 6.6;
      if (corridor || niche) rows[static_cast<size_t>(r)][static_cast<size_t>(c)] = '.';
    }
  }
  return test::grid_from_art(rows, 0.1);
}

TEST(TrafficRules, FarApartRobotsAllGo) {
  const PlanningGrid grid = test::uniform_grid(100, 100, kCellFree, 0.1);
  std::vector<Bot> bots{{{1, 1}, {{4, 1}}, 0}, {{1, 8}, {{4, 8}}, 1}};
  TrafficRules rules{CoordinationConfig{}};
  std::vector<TrafficDecision> decisions;
  rules.decide(grid, inputs(bots), 0, decisions);
  ASSERT_EQ(decisions.size(), 2u);
  EXPECT_EQ(decisions[0].order, TrafficOrder::Go);
  EXPECT_EQ(decisions[1].order, TrafficOrder::Go);
}

TEST(TrafficRules, LaterRouteWaitsAtACrossingAndTheEarlierGoes) {
  const PlanningGrid grid = test::uniform_grid(100, 100, kCellFree, 0.1);
  // Paths cross at (5, 5); robot 1 started its route later.
  std::vector<Bot> bots{{{4, 5}, {{8, 5}}, 0}, {{5, 3.5}, {{5, 8}}, 1000}};
  TrafficRules rules{CoordinationConfig{}};
  std::vector<TrafficDecision> decisions;
  rules.decide(grid, inputs(bots), 0, decisions);
  EXPECT_EQ(decisions[0].order, TrafficOrder::Go);
  EXPECT_EQ(decisions[1].order, TrafficOrder::Wait);
  EXPECT_EQ(decisions[1].blocker, 0);
  EXPECT_EQ(decisions[1].waiting_since_ns, 0);
  // Swap the ages: the other one goes first.
  std::swap(bots[0].since_ns, bots[1].since_ns);
  TrafficRules swapped{CoordinationConfig{}};
  decisions.clear();
  swapped.decide(grid, inputs(bots), 0, decisions);
  EXPECT_EQ(decisions[0].order, TrafficOrder::Wait);
  EXPECT_EQ(decisions[1].order, TrafficOrder::Go);
}

TEST(TrafficRules, NoseToNoseIsADeadlockTheLaterRouteYields) {
  const PlanningGrid grid = test::uniform_grid(100, 100, kCellFree, 0.1);
  // Neither can move without nearing the other: a wait-for cycle.
  std::vector<Bot> bots{{{4.6, 5}, {{9, 5}}, 0}, {{5.4, 5}, {{1, 5}}, 10}};
  TrafficRules rules{CoordinationConfig{}};
  std::vector<TrafficDecision> decisions;
  rules.decide(grid, inputs(bots), 0, decisions);
  EXPECT_EQ(rules.deadlocks(), 1u);
  EXPECT_EQ(decisions[0].order, TrafficOrder::Wait);
  EXPECT_EQ(decisions[1].order, TrafficOrder::Yield);
  EXPECT_TRUE(decisions[1].deadlock);
  // Steps off the line the other drives along.
  EXPECT_GT(std::abs(decisions[1].hold.y - 5.0), 0.2);
}

TEST(TrafficRules, StoppedRobotInTheWayStepsAside) {
  const PlanningGrid grid = test::uniform_grid(100, 100, kCellFree, 0.1);
  std::vector<Bot> bots{{{2, 5}, {{8, 5}}, 0}, {{3, 5}, {}, 0}};  // robot 1 has no route
  TrafficRules rules{CoordinationConfig{}};
  std::vector<TrafficDecision> decisions;
  rules.decide(grid, inputs(bots), 0, decisions);
  EXPECT_EQ(decisions[0].order, TrafficOrder::Wait);
  EXPECT_EQ(decisions[1].order, TrafficOrder::Yield);
  EXPECT_EQ(decisions[0].waiting_since_ns, 0);
  EXPECT_EQ(decisions[1].waiting_since_ns, -1);  // no route: it does not count as waiting
}

TEST(TrafficRules, OppositeDirectionsThroughOneDoorBothArriveApart) {
  const PlanningGrid grid = door_room();
  std::vector<Bot> bots{{{2, 3}, {{4.5, 5}, {5.5, 5}, {8, 7}}, 0}, {{8, 3}, {{5.5, 5}, {4.5, 5}, {2, 7}}, 1}};
  const RunResult r = run(grid, bots, CoordinationConfig{}, 4000);
  EXPECT_TRUE(r.all_arrived);
  EXPECT_GE(r.closest, 2.0 * CoordinationConfig{}.robot_radius_m);
}

TEST(TrafficRules, WithoutTheRulesTheSameDoorRunMeets) {
  // The scenario above is a real test: robots that ignore each other get within one body.
  const PlanningGrid grid = door_room();
  std::vector<Bot> bots{{{2, 3}, {{4.5, 5}, {5.5, 5}, {8, 7}}, 0}, {{8, 3}, {{5.5, 5}, {4.5, 5}, {2, 7}}, 1}};
  double closest = std::numeric_limits<double>::infinity();
  for (int step = 0; step < 4000; ++step) {
    for (Bot& b : bots) {
      if (b.arrived()) continue;
      const Vec2 target = b.path[b.next];
      const double gap = distance(b.position, target);
      b.position = gap <= kSpeed * kDt ? target : b.position + (target - b.position) * (kSpeed * kDt / gap);
      if (distance(b.position, target) < kArrive) ++b.next;
    }
    closest = std::min(closest, distance(bots[0].position, bots[1].position));
  }
  EXPECT_LT(closest, 2.0 * CoordinationConfig{}.robot_radius_m);
}

TEST(TrafficRules, HeadOnInACorridorTheLaterRouteUsesTheNiche) {
  const PlanningGrid grid = corridor_with_niche();
  std::vector<Bot> bots{{{1.5, 5}, {{9, 5}}, 0}, {{8.5, 5}, {{1, 5}}, 1}};
  const RunResult r = run(grid, bots, CoordinationConfig{}, 6000);
  EXPECT_TRUE(r.all_arrived);
  EXPECT_GE(r.closest, 2.0 * CoordinationConfig{}.robot_radius_m);
  EXPECT_GT(r.yields, 0u);
}

TEST(TrafficRules, WhenTheLowerPriorityCannotStepAsideTheOtherOneDoes) {
  // Nose to nose; the only niche lies behind the robot that goes first.
  const PlanningGrid grid = corridor_with_niche(5.8, 6.6);
  std::vector<Bot> bots{{{5.4, 5}, {{1, 5}}, 0}, {{4.6, 5}, {{9, 5}}, 10}};
  TrafficRules rules{CoordinationConfig{}};
  std::vector<TrafficDecision> decisions;
  rules.decide(grid, inputs(bots), 0, decisions);
  EXPECT_EQ(rules.deadlocks(), 1u);
  EXPECT_EQ(decisions[0].order, TrafficOrder::Yield);
  EXPECT_EQ(decisions[1].order, TrafficOrder::Wait);
  const RunResult r = run(grid, bots, CoordinationConfig{}, 6000);
  EXPECT_TRUE(r.all_arrived);
  EXPECT_GE(r.closest, 2.0 * CoordinationConfig{}.robot_radius_m);
  EXPECT_EQ(r.deadlocks, 1u);  // one cycle, counted once however long it takes to clear
}

// Two rooms (x 0.5..5 m and 11..15.5 m, y 0.5..7.5 m) joined by a single-lane corridor 0.6 m wide
// and 6 m long along y = 4 m.
CoordinationConfig with_sections() {
  CoordinationConfig c;
  c.one_way_sections = true;
  return c;
}

PlanningGrid rooms_and_corridor() {
  std::vector<std::string> rows(80, std::string(160, '#'));
  for (int r = 0; r < 80; ++r) {
    const double y = (79 - r + 0.5) * 0.1;
    for (int c = 0; c < 160; ++c) {
      const double x = (c + 0.5) * 0.1;
      const bool room = y > 0.5 && y < 7.5 && ((x > 0.5 && x < 5.0) || (x > 11.0 && x < 15.5));
      const bool corridor = y > 3.7 && y < 4.3 && x >= 5.0 && x <= 11.0;
      if (room || corridor) rows[static_cast<size_t>(r)][static_cast<size_t>(c)] = '.';
    }
  }
  return test::grid_from_art(rows, 0.1);
}

TEST(TrafficRules, RobotWaitsBeforeACorridorUsedTheOtherWayEvenWithHigherPriority) {
  const PlanningGrid grid = rooms_and_corridor();
  // a is in the corridor going right; b, the earlier route, is about to enter it going left.
  std::vector<Bot> bots{{{7.0, 4.0}, {{11.0, 4.0}, {13.0, 4.0}}, 10},
                        {{12.2, 4.0}, {{11.0, 4.0}, {5.0, 4.0}, {2.0, 4.0}}, 0}};
  TrafficRules rules{with_sections()};
  std::vector<TrafficDecision> decisions;
  rules.decide(grid, inputs(bots), 0, decisions);
  EXPECT_EQ(decisions[0].order, TrafficOrder::Go);
  EXPECT_EQ(decisions[1].order, TrafficOrder::Wait);
  EXPECT_TRUE(decisions[1].section);
  EXPECT_EQ(decisions[1].blocker, 0);
  // It waits outside, clear of the mouth: a reach (two radii and the clearance) before it.
  const CoordinationConfig c = with_sections();
  EXPECT_GE(decisions[1].hold.x, 11.0 + 2.0 * c.robot_radius_m + c.clearance_m - 0.15);
  EXPECT_LE(decisions[1].hold.x, 12.2);
}

TEST(TrafficRules, BothOutsideTheEarlierRouteTakesTheCorridorTheOtherWaits) {
  const PlanningGrid grid = rooms_and_corridor();
  std::vector<Bot> bots{{{4.0, 4.0}, {{5.0, 4.0}, {11.0, 4.0}, {13.0, 4.0}}, 10},
                        {{12.0, 4.0}, {{11.0, 4.0}, {5.0, 4.0}, {2.0, 4.0}}, 0}};
  TrafficRules rules{with_sections()};
  std::vector<TrafficDecision> decisions;
  rules.decide(grid, inputs(bots), 0, decisions);
  EXPECT_EQ(decisions[0].order, TrafficOrder::Wait);
  EXPECT_TRUE(decisions[0].section);
  EXPECT_EQ(decisions[1].order, TrafficOrder::Go);
}

TEST(TrafficRules, AStreamOneWayDoesNotStarveAnEarlierRouteWaitingTheOtherWay) {
  const PlanningGrid grid = rooms_and_corridor();
  // a is inside going right; b (earliest route) waits at the right end; c (latest) comes to the left
  // end going right, the way a goes: it waits for b instead of following a in.
  std::vector<Bot> bots{{{8.0, 4.0}, {{11.0, 4.0}, {13.0, 4.0}}, 5},
                        {{12.2, 4.0}, {{11.0, 4.0}, {5.0, 4.0}, {2.0, 4.0}}, 0},
                        {{4.0, 4.0}, {{5.0, 4.0}, {11.0, 4.0}, {14.0, 6.0}}, 10}};
  TrafficRules rules{with_sections()};
  std::vector<TrafficDecision> decisions;
  rules.decide(grid, inputs(bots), 0, decisions);
  EXPECT_EQ(decisions[0].order, TrafficOrder::Go);
  EXPECT_EQ(decisions[1].order, TrafficOrder::Wait);
  EXPECT_EQ(decisions[1].blocker, 0);
  EXPECT_EQ(decisions[2].order, TrafficOrder::Wait);
  EXPECT_TRUE(decisions[2].section);
  EXPECT_EQ(decisions[2].blocker, 1);
}

// Three robots queue into the corridor from each end (the maze jam: with 2 m reservations alone the
// two fronts meet inside and the queues behind them leave neither a way back). Counts the steps in
// which robots inside the corridor head both ways.
struct QueueRun {
  RunResult result;
  int both_ways = 0;
  size_t robots = 0;
};

QueueRun queues_from_both_ends(const CoordinationConfig& config) {
  const PlanningGrid grid = rooms_and_corridor();
  std::vector<Bot> bots;
  const std::vector<Vec2> right_targets{{12.5, 6.5}, {13.5, 1.5}, {15.0, 4.0}};
  const std::vector<Vec2> left_targets{{3.5, 6.5}, {2.5, 1.5}, {1.0, 4.0}};
  for (int k = 0; k < 3; ++k) {
    bots.push_back(
        Bot{{4.4 - 0.8 * k, 4.0}, {{5.0, 4.0}, {11.0, 4.0}, right_targets[static_cast<size_t>(k)]}, 2 * k});
    bots.push_back(Bot{
        {11.6 + 0.8 * k, 4.0}, {{11.0, 4.0}, {5.0, 4.0}, left_targets[static_cast<size_t>(k)]}, 2 * k + 1});
  }
  QueueRun out;
  out.robots = bots.size();
  const auto count_both_ways = [&](const std::vector<Bot>& now) {
    bool right = false, left = false;
    for (const Bot& b : now) {
      if (b.arrived() || b.position.x < 5.0 || b.position.x > 11.0) continue;
      (b.path.back().x > b.position.x ? right : left) = true;
    }
    if (right && left) ++out.both_ways;
  };
  out.result = run(grid, bots, config, 12000, count_both_ways);
  return out;
}

TEST(TrafficRules, QueuesFromBothEndsOfACorridorAllGetThroughWithinTheBound) {
  const CoordinationConfig config = with_sections();
  const QueueRun q = queues_from_both_ends(config);
  EXPECT_EQ(q.both_ways, 0);  // the corridor is one-way at any time
  EXPECT_TRUE(q.result.all_arrived);
  EXPECT_GE(q.result.closest, 2.0 * config.robot_radius_m);
  // The header's bound: the robots ranked above one each cross the stretch once.
  const double stretch_m = 6.0;
  const double bound_s = (static_cast<double>(q.robots) - 1.0) * (stretch_m + config.lookahead_m) / kSpeed;
  EXPECT_LE(q.result.longest_wait_s, bound_s);
}

TEST(TrafficRules, WithoutSectionsTheQueuesMeetInsideTheCorridor) {
  // The scenario above is a real test of the sections: without them robots enter from both ends.
  EXPECT_GT(queues_from_both_ends(CoordinationConfig{}).both_ways, 0);
}

TEST(TrafficRules, TenRobotsCrossingARoomNeverMeet) {
  const PlanningGrid grid = test::uniform_grid(120, 120, kCellFree, 0.1);
  std::vector<Bot> bots;
  // Five robots on the left going right and five on the right going left, lanes interleaved.
  for (int k = 0; k < 5; ++k) {
    const double y = 2.0 + 2.0 * k;
    bots.push_back(Bot{{1.0, y}, {{11.0, 12.0 - y}}, k});
    bots.push_back(Bot{{11.0, y + 0.5}, {{1.0, 11.5 - y}}, 5 + k});
  }
  const RunResult r = run(grid, bots, CoordinationConfig{}, 20000);
  EXPECT_TRUE(r.all_arrived);
  EXPECT_GE(r.closest, 2.0 * CoordinationConfig{}.robot_radius_m);
}

// Two corridors along y = 5 m and y = 7 m joined at both ends: a loop.
PlanningGrid two_corridors() {
  std::vector<std::string> rows(100, std::string(100, '#'));
  for (int r = 0; r < 100; ++r) {
    const double y = (99 - r + 0.5) * 0.1;
    for (int c = 0; c < 100; ++c) {
      const double x = (c + 0.5) * 0.1;
      const bool lower = y > 4.6 && y < 5.4 && x > 1.0 && x < 9.0;
      const bool upper = y > 6.6 && y < 7.4 && x > 1.0 && x < 9.0;
      const bool ends = y > 4.6 && y < 7.4 && ((x > 1.0 && x < 1.8) || (x > 8.2 && x < 9.0));
      if (lower || upper || ends) rows[static_cast<size_t>(r)][static_cast<size_t>(c)] = '.';
    }
  }
  return test::grid_from_art(rows, 0.1);
}

TEST(FleetCoordinator, RobotHeldByAStoppedRobotThatCannotMovePlansAroundIt) {
  const PlanningGrid grid = two_corridors();
  Fleet fleet{FleetConfig{}};
  fleet.observe("a", {4.0, 5.0});
  fleet.observe("b", {5.0, 5.0});  // no goal: it stands in the lower corridor
  ASSERT_TRUE(fleet.set_goal("a", Goal{1, GoalMode::Planned, {8.5, 5.0}}));
  fleet.tick(grid, 0);
  ASSERT_FALSE(fleet.tracker("a")->remaining().empty());
  CoordinationConfig config;
  config.yield_search_m = 0.3;  // b finds no place to step aside to
  config.replan_after_s = 1.0;
  FleetCoordinator coordinator(config);
  coordinator.observe("a", {4.0, 5.0});
  coordinator.observe("b", {5.0, 5.0});
  coordinator.coordinate(fleet, grid, 0);
  EXPECT_EQ(coordinator.order("a"), TrafficOrder::Wait);
  EXPECT_EQ(coordinator.replans(), 0u);
  coordinator.coordinate(fleet, grid, 1'500'000'000);
  EXPECT_EQ(coordinator.replans(), 1u);
  // The new route keeps clear of b: through the upper corridor.
  const auto rest = fleet.tracker("a")->remaining();
  ASSERT_FALSE(rest.empty());
  Vec2 from{4.0, 5.0};
  for (const Vec2& p : rest) {
    EXPECT_GE(distance_to_segment({5.0, 5.0}, from, p), 2.0 * config.robot_radius_m);
    from = p;
  }
  coordinator.coordinate(fleet, grid, 1'600'000'000);
  EXPECT_EQ(coordinator.order("a"), TrafficOrder::Go);
}

TEST(FleetCoordinator, AForgottenRobotNoLongerHoldsAnyone) {
  const PlanningGrid grid = two_corridors();
  Fleet fleet{FleetConfig{}};
  fleet.observe("a", {4.0, 5.0});
  fleet.observe("b", {5.0, 5.0});
  ASSERT_TRUE(fleet.set_goal("a", Goal{1, GoalMode::Planned, {8.5, 5.0}}));
  fleet.tick(grid, 0);
  FleetCoordinator coordinator{CoordinationConfig{}};
  coordinator.observe("a", {4.0, 5.0});
  coordinator.observe("b", {5.0, 5.0});
  coordinator.coordinate(fleet, grid, 0);
  EXPECT_NE(coordinator.order("a"), TrafficOrder::Go);
  coordinator.forget("b");
  coordinator.coordinate(fleet, grid, 100'000'000);
  EXPECT_EQ(coordinator.order("a"), TrafficOrder::Go);
}

TEST(CoordinationConfig, ValidationNamesTheKey) {
  CoordinationConfig c;
  EXPECT_TRUE(validate(c));
  c.lookahead_m = 0.0;
  EXPECT_NE(validate(c).message().find("lookahead_m"), std::string::npos);
  c = CoordinationConfig{};
  c.body_lookahead_m = c.lookahead_m + 1.0;
  EXPECT_NE(validate(c).message().find("body_lookahead_m"), std::string::npos);
}

TEST(CoordinationOptions, OnByDefaultOffKeepsEveryRobotOnItsRoute) {
  PlannerOptions defaults;
  EXPECT_TRUE(defaults.coordination.enabled);
  for (const auto& [value, enabled] : {std::pair{"off", false}, std::pair{"on", true}}) {
    PlannerOptions o;
    CLI::App app{"test"};
    add_planner_options(app, o);
    // CLI11 takes the arguments reversed.
    ASSERT_NO_THROW(
        app.parse(std::vector<std::string>{"3.0", "--coordination-lookahead-m", value, "--coordination"}));
    EXPECT_EQ(o.coordination.enabled, enabled);
    EXPECT_DOUBLE_EQ(o.coordination.lookahead_m, 3.0);
    EXPECT_FALSE(o.coordination.one_way_sections);
    EXPECT_TRUE(validate(o));
  }
  PlannerOptions sections;
  CLI::App sections_app{"test"};
  add_planner_options(sections_app, sections);
  ASSERT_NO_THROW(sections_app.parse(std::vector<std::string>{"on", "--coordination-sections"}));
  EXPECT_TRUE(sections.coordination.one_way_sections);
  PlannerOptions clearing;
  CLI::App clearing_app{"test"};
  add_planner_options(clearing_app, clearing);
  const bool by_default = clearing.coordination.clear_way;
  ASSERT_NO_THROW(clearing_app.parse(std::vector<std::string>{
      "2.5", "--coordination-clear-after-s", by_default ? "off" : "on", "--coordination-clear-way"}));
  EXPECT_NE(clearing.coordination.clear_way, by_default);
  EXPECT_DOUBLE_EQ(clearing.coordination.clear_after_s, 2.5);
  PlannerOptions bad;
  CLI::App app{"test"};
  add_planner_options(app, bad);
  EXPECT_ANY_THROW(app.parse(std::vector<std::string>{"maybe", "--coordination"}));
}

}  // namespace
}  // namespace slam::planner
