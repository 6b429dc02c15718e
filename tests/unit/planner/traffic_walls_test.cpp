// The traffic rules against the walls: a robot pushed along a leader's route is never sent on a
// straight way that runs into a wall (it would stop against it for good: simulated and legacy
// robots drive straight at their waypoint), and a robot released off its route plans again when
// the straight way back would hit a wall.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "grid_builder.hpp"
#include "planner/core/fleet.hpp"
#include "planner/core/fleet_coordinator.hpp"
#include "planner/core/traffic_geometry.hpp"

namespace slam::planner {
namespace {

struct Box {
  double x0, y0, x1, y1;
};

// A 10 m x 10 m grid at 0.1 m: free except the walls (occupied boxes), and with `inflation` the
// cells within that distance of a wall inflated, as the mapper publishes them.
PlanningGrid walls(const std::vector<Box>& boxes, double inflation = 0.0) {
  const auto gap = [&](double x, double y) {
    double best = 1e9;
    for (const Box& b : boxes)
      best = std::min(best,
                      std::hypot(std::max({b.x0 - x, 0.0, x - b.x1}), std::max({b.y0 - y, 0.0, y - b.y1})));
    return best;
  };
  std::vector<std::string> rows(100, std::string(100, '.'));
  for (size_t r = 0; r < rows.size(); ++r) {
    const double y = (99.0 - static_cast<double>(r) + 0.5) * 0.1;
    for (size_t c = 0; c < rows[r].size(); ++c) {
      const double x = (static_cast<double>(c) + 0.5) * 0.1;
      const double g = gap(x, y);
      if (g == 0.0) {
        rows[r][c] = '#';
      } else if (g < inflation) {
        rows[r][c] = 'i';
      }
    }
  }
  return test::grid_from_art(rows, 0.1);
}

constexpr double kRadius = 0.2;

TEST(TrafficWalls, AStraightWayPastAWallsCornerIsRefusedThoughBothEndsAreFree) {
  const PlanningGrid grid = walls({{5.0, 0.0, 5.2, 5.0}});  // a wall ending at (5.1, 5.0)
  // Both ends are 0.5 m from the wall; the way between them cuts past its end 0.07 m off it.
  EXPECT_FALSE(traffic::keeps_off_walls(grid, {4.5, 4.5}, {5.7, 5.2}, kRadius));
  // Round the end with room to spare: fine.
  EXPECT_TRUE(traffic::keeps_off_walls(grid, {4.5, 4.5}, {4.5, 5.6}, kRadius));
  EXPECT_TRUE(traffic::keeps_off_walls(grid, {4.5, 5.6}, {5.7, 5.6}, kRadius));
}

TEST(TrafficWalls, ARobotPressedAgainstAWallMayOnlyDriveAwayFromIt) {
  const PlanningGrid grid = walls({{5.0, 0.0, 5.2, 5.0}});
  const Vec2 pressed{4.85, 3.0};  // 0.15 m from the wall's face: nearer than the radius
  EXPECT_TRUE(traffic::keeps_off_walls(grid, pressed, {3.8, 3.0}, kRadius));   // straight away
  EXPECT_FALSE(traffic::keeps_off_walls(grid, pressed, {5.0, 3.5}, kRadius));  // into it
  // Round the wall's end from beside it: the body would scrape the end on the way.
  EXPECT_FALSE(traffic::keeps_off_walls(grid, {4.85, 4.9}, {5.4, 5.3}, kRadius));
}

// An L of single-lane corridors (0.8 m wide, no room to step aside anywhere): east along y = 5 m to
// x = 5 m, then north to a dead end at y = 9.2 m. The leader drives east and round the bend to the
// end; the robot on its way has no side room, so it is pushed on ahead along the leader's route.
TEST(TrafficWalls, ARobotPushedAlongTheLeadersRouteIsNotSentPastTheBendsCorner) {
  const PlanningGrid grid =
      walls({{0.0, 0.0, 10.0, 4.6}, {0.0, 5.4, 4.6, 10.0}, {5.4, 4.6, 10.0, 10.0}, {4.6, 9.2, 5.4, 10.0}});
  // Pressed up against the corridor's north wall 0.12 m short of the bend's inner corner (4.6, 5.4)
  // m: straight to a point a metre on along the route (round the bend) it would scrape the corner.
  const Vec2 pushed{4.3, 5.28};
  std::vector<TrafficRobot> robots{{{3.2, 5.0}, {}, 0, 0}, {pushed, {}, 0, 1}};
  const std::vector<Vec2> route{{5.0, 5.0}, {5.0, 9.0}};
  robots[0].ahead = route;
  TrafficRules rules{CoordinationConfig{}};
  std::vector<TrafficDecision> decisions;
  rules.decide(grid, robots, 0, decisions);
  ASSERT_EQ(decisions[0].order, TrafficOrder::Wait);  // the robot ahead is in its way
  rules.decide(grid, robots, 6'000'000'000, decisions);
  ASSERT_EQ(rules.leader(), 0);
  ASSERT_EQ(decisions[1].order, TrafficOrder::Yield);
  EXPECT_TRUE(traffic::keeps_off_walls(grid, pushed, decisions[1].hold, kRadius));
  // Back onto the route first: the robot is moved, not left standing.
  EXPECT_GT(distance(decisions[1].hold, pushed), 0.1);
}

TEST(TrafficWalls, ALeaderWhosePushedRobotDoesNotMoveGivesTheLeadUp) {
  // The same bend; the pushed robot is sent on every tick but never gets anywhere (held by a wall
  // or a robot the planner cannot see). Sending it is no progress: after clear_stall_s of
  // neither the leader nor it moving, the lead is given up and chosen afresh.
  const PlanningGrid grid =
      walls({{0.0, 0.0, 10.0, 4.6}, {0.0, 5.4, 4.6, 10.0}, {5.4, 4.6, 10.0, 10.0}, {4.6, 9.2, 5.4, 10.0}});
  std::vector<TrafficRobot> robots{{{3.2, 5.0}, {}, 0, 0}, {{4.3, 5.0}, {}, 0, 1}};
  const std::vector<Vec2> route{{5.0, 5.0}, {5.0, 9.0}};
  robots[0].ahead = route;
  const CoordinationConfig config;
  TrafficRules rules{config};
  std::vector<TrafficDecision> decisions;
  const auto at = [](double s) { return static_cast<int64_t>(s * 1e9); };
  for (double t = 0.0; t < config.clear_after_s + config.clear_stall_s + 2.0; t += 0.05) {
    rules.decide(grid, robots, at(t), decisions);
    if (rules.leader() == 0) {
      EXPECT_EQ(decisions[1].order, TrafficOrder::Yield);
    }
  }
  EXPECT_EQ(rules.clearings(), 2u);
}

TEST(FleetCoordinator, ARobotReleasedBesideAPillarPlansAgainInsteadOfDrivingIntoIt) {
  // A pillar at x 3.4..5 m, y 3..4 m, inflated like the mapper's; the route runs north past its
  // west face along x = 3 m.
  const PlanningGrid grid = walls({{3.4, 3.0, 5.0, 4.0}}, kRadius);
  Fleet fleet{FleetConfig{}};
  fleet.observe("a", {3.0, 1.0});
  ASSERT_TRUE(fleet.set_goal("a", Goal{1, GoalMode::Planned, {3.0, 6.0}}));
  fleet.tick(grid, 0);
  const GoalTracker* t = fleet.tracker("a");
  ASSERT_TRUE(t->current_waypoint());
  // It stepped aside under the pillar, 0.65 m off its leg (not far enough to count as strayed):
  // straight from there to its waypoint runs into the pillar.
  const Vec2 aside{3.65, 2.7};
  fleet.observe("a", aside);
  ASSERT_FALSE(t->needs_plan());
  ASSERT_FALSE(traffic::keeps_off_walls(grid, aside, *t->current_waypoint(), kRadius));
  FleetCoordinator coordinator{CoordinationConfig{}};
  coordinator.observe("a", aside);
  coordinator.coordinate(fleet, grid, 0);
  EXPECT_EQ(coordinator.order("a"), TrafficOrder::Go);
  EXPECT_EQ(coordinator.replans(), 1u);
  ASSERT_TRUE(t->current_waypoint());
  EXPECT_TRUE(traffic::keeps_off_walls(grid, aside, *t->current_waypoint(), kRadius));
}

}  // namespace
}  // namespace slam::planner
