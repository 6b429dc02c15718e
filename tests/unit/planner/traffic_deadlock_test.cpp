// Deadlock rules of the traffic rules, each on a scenario that the rule alone resolves: (a) a member
// of a wait-for cycle steps off the way of the robot waiting for it, (b) the queues behind a cycle
// with no room back off first, and the leader rule clears a single-lane jam into a side branch out of
// reach of any local step aside.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "grid_builder.hpp"
#include "planner/core/fleet_coordinator.hpp"
#include "traffic_run.hpp"

namespace slam::planner {
namespace {

using test::Bot;
using test::inputs;
using test::run;
using test::RunResult;

struct Box {
  double x0, y0, x1, y1;
};

// A 0.1 m grid `width_m` x 10 m, walls everywhere but the boxes.
PlanningGrid boxes(double width_m, const std::vector<Box>& free) {
  const auto cols = static_cast<size_t>(width_m * 10.0);
  std::vector<std::string> rows(100, std::string(cols, '#'));
  for (size_t r = 0; r < rows.size(); ++r) {
    const double y = (99.0 - static_cast<double>(r) + 0.5) * 0.1;
    for (size_t c = 0; c < cols; ++c) {
      const double x = (static_cast<double>(c) + 0.5) * 0.1;
      for (const Box& b : free)
        if (x > b.x0 && x < b.x1 && y > b.y0 && y < b.y1) rows[r][c] = '.';
    }
  }
  return test::grid_from_art(rows, 0.1);
}

CoordinationConfig local_rules_only() {
  CoordinationConfig c;
  c.clear_way = false;
  return c;
}

// Rule (a). Three robots in a triangle, each heading at the next one's body: B waits for C, C for A,
// A for B. C (the highest tie number) moves: off the way of B, which waits for it. Off the way of A
// (the one C waits for) it would already be, and would stay on B's way: the cycle would remain.
TEST(TrafficRules, InACycleOfThreeTheMemberStepsOffTheWayOfTheRobotWaitingForIt) {
  const PlanningGrid grid = test::uniform_grid(100, 100, kCellFree, 0.1);
  const Vec2 b{5.0, 5.0}, c{5.7, 5.0}, a{5.35, 5.6};
  std::vector<Bot> bots{{a, {a + (b - a) * 4.0}, 0}, {b, {{9.5, 5.0}}, 1}, {c, {c + (a - c) * 4.0}, 2}};
  TrafficRules rules{local_rules_only()};
  std::vector<TrafficDecision> decisions;
  rules.decide(grid, inputs(bots), 0, decisions);
  ASSERT_EQ(rules.deadlocks(), 1u);
  EXPECT_EQ(decisions[0].order, TrafficOrder::Wait);
  EXPECT_EQ(decisions[1].order, TrafficOrder::Wait);
  ASSERT_EQ(decisions[2].order, TrafficOrder::Yield);
  EXPECT_EQ(decisions[2].blocker, 1);
  // Its place is off B's way along y = 5 m.
  EXPECT_GE(std::abs(decisions[2].hold.y - 5.0), 2.0 * CoordinationConfig{}.robot_radius_m);
  const RunResult r = run(grid, bots, local_rules_only(), 4000);
  EXPECT_TRUE(r.all_arrived);
  EXPECT_GE(r.closest, 2.0 * CoordinationConfig{}.robot_radius_m);
}

// Rule (b). Nose to nose in a single-lane corridor (y = 5 m): A heading east with C queued behind
// it, B heading west. Neither A nor B has room: B's side has none, and A's way back to the side
// room at the corridor's west end passes C. C, queued behind A, steps into the room first.
TEST(TrafficRules, WhenNoMemberOfACycleHasRoomTheQueueBehindItBacksOffFirst) {
  const PlanningGrid grid = boxes(10.0, {{0.5, 4.7, 9.5, 5.3}, {0.6, 5.2, 3.0, 9.5}});
  std::vector<Bot> bots{{{3.6, 5}, {{9.0, 5}}, 0}, {{4.4, 5}, {{1.0, 5}}, 1}, {{2.8, 5}, {{8.3, 5}}, 2}};
  for (Bot& b : bots) b.retrace = true;
  TrafficRules rules{local_rules_only()};
  std::vector<TrafficDecision> decisions;
  rules.decide(grid, inputs(bots), 0, decisions);
  EXPECT_EQ(rules.deadlocks(), 1u);
  EXPECT_EQ(decisions[0].order, TrafficOrder::Wait);
  EXPECT_EQ(decisions[1].order, TrafficOrder::Wait);
  EXPECT_EQ(decisions[2].order, TrafficOrder::Yield);
  // The local rules alone then stall (C stops half into the room once A moves, and waits for A);
  // the leader rule finishes it.
  const RunResult r = run(grid, bots, CoordinationConfig{}, 12000);
  EXPECT_TRUE(r.all_arrived);
  EXPECT_GE(r.closest, 2.0 * CoordinationConfig{}.robot_radius_m);
}

// The leader rule. A single-lane corridor (y = 5 m) from a room at its west end (x < 2.5 m) to
// x = 14.5 m, with one single-lane side branch at x 12.1..12.7 m: the leader heading east meets three
// robots heading west into the room. Neither the room (3.5 m behind the leader) nor the branch
// (3.5 m ahead of the last robot) is within reach of a local step aside (yield_search_m, 3 m), so
// only clearing the leader's way gets anyone through.
std::vector<Bot> jam_before_a_branch() {
  std::vector<Bot> bots{{{6.0, 5}, {{14.0, 5}}, 0}};
  const std::vector<Vec2> in_the_room{{1.0, 6.3}, {1.0, 3.7}, {2.0, 5.0}};
  for (size_t k = 0; k < 3; ++k)
    bots.push_back(Bot{
        {7.0 + 0.8 * static_cast<double>(k), 5}, {{2.5, 5}, in_the_room[k]}, 1 + static_cast<int64_t>(k)});
  for (Bot& b : bots) b.retrace = true;
  return bots;
}

PlanningGrid corridor_with_branch() {
  return boxes(15.0, {{0.5, 3.0, 2.6, 7.0}, {2.5, 4.7, 14.5, 5.3}, {12.1, 5.2, 12.7, 8.8}});
}

TEST(TrafficRules, TheRobotWaitingLongestLeadsAndTheRobotsOnItsWayArePushed) {
  const PlanningGrid grid = corridor_with_branch();
  const std::vector<Bot> bots = jam_before_a_branch();
  const CoordinationConfig config;
  TrafficRules rules{config};
  std::vector<TrafficDecision> decisions;
  rules.decide(grid, inputs(bots), 0, decisions);
  EXPECT_EQ(rules.clearings(), 0u);
  // Nobody moved: once the waits pass clear_after_s the earliest route (robot 0) leads.
  const auto later = static_cast<int64_t>((config.clear_after_s + 1.0) * 1e9);
  rules.decide(grid, inputs(bots), later, decisions);
  EXPECT_EQ(rules.clearings(), 1u);
  // The robot furthest along the leader's way heads for the branch; the ones behind it wait for it.
  EXPECT_EQ(decisions[3].order, TrafficOrder::Yield);
  EXPECT_EQ(decisions[3].blocker, 0);
  EXPECT_GT(decisions[3].hold.x, bots[3].position.x);
  for (const size_t k : {1u, 2u}) {
    EXPECT_EQ(decisions[k].order, TrafficOrder::Wait);
    EXPECT_EQ(decisions[k].blocker, 0);
  }
}

TEST(TrafficRules, TheLeaderClearsAJamIntoASideBranchOutOfReachOfAStepAside) {
  const PlanningGrid grid = corridor_with_branch();
  std::vector<Bot> bots = jam_before_a_branch();
  const RunResult r = run(grid, bots, CoordinationConfig{}, 20000);
  EXPECT_TRUE(r.all_arrived);
  EXPECT_GE(r.closest, 2.0 * CoordinationConfig{}.robot_radius_m);
  // Bounded: the leader waits clear_after_s, the three drive into the branch and out again.
  EXPECT_LE(r.longest_wait_s, 120.0);
}

TEST(TrafficRules, WithoutTheLeaderRuleTheSameJamNeverClears) {
  const PlanningGrid grid = corridor_with_branch();
  std::vector<Bot> bots = jam_before_a_branch();
  const RunResult r = run(grid, bots, local_rules_only(), 20000);
  EXPECT_FALSE(r.all_arrived);
}

}  // namespace
}  // namespace slam::planner
