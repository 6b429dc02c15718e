// StartEscape, segment_clear_leaving and PathPlanner::plan_for_robot: a robot standing in an
// inflated or unexplored cell still gets a path, through the nearest passable cell beside it.
#include "planner/core/start_escape.hpp"

#include <gtest/gtest.h>

#include "grid_builder.hpp"
#include "planner/core/line_of_sight.hpp"
#include "planner/core/path_planner.hpp"

namespace slam::planner {
namespace {

TEST(StartEscape, PassableStartIsItsOwnEscape) {
  const PlanningGrid g = test::grid_from_art({"...", "...", "..."});
  StartEscape e;
  EXPECT_EQ(e.find(g, {1, 1}, 3.0, UnknownPolicy::Blocked), (Cell{1, 1}));
}

TEST(StartEscape, LeavesAnInflatedCellForTheNearestFreeOne) {
  const PlanningGrid g = test::grid_from_art({
      "#iii....",
      "#iii....",
      "#ii.....",
      "#iii....",
  });
  StartEscape e;
  // From (1, 1) the free cell (3, 1) is two cells away; (4, 0..3) are farther.
  EXPECT_EQ(e.find(g, {1, 1}, 4.0, UnknownPolicy::Blocked), (Cell{3, 1}));
  // Too far for a one-cell radius.
  EXPECT_FALSE(e.find(g, {1, 1}, 1.0, UnknownPolicy::Blocked));
}

TEST(StartEscape, NeverCrossesAWall) {
  // The free cells on the left are nearer, but behind a wall; the way out is to the right.
  const PlanningGrid g = test::grid_from_art({
      "..#iii....",
      "..#iii....",
      "..#iii....",
  });
  StartEscape e;
  EXPECT_EQ(e.find(g, {3, 1}, 4.0, UnknownPolicy::Blocked), (Cell{6, 1}));
  // Nor squeezes diagonally between two wall cells.
  const PlanningGrid corner = test::grid_from_art({
      ".#.",
      "#i#",
      "###",
  });
  EXPECT_FALSE(e.find(corner, {1, 1}, 3.0, UnknownPolicy::Blocked));
}

TEST(StartEscape, UnknownCellsAreLeftTooUnlessAllowed) {
  const PlanningGrid g = test::grid_from_art({"???..", "???..", "???.."});
  StartEscape e;
  EXPECT_EQ(e.find(g, {1, 1}, 3.0, UnknownPolicy::Blocked), (Cell{3, 1}));
  EXPECT_EQ(e.find(g, {1, 1}, 3.0, UnknownPolicy::Allowed), (Cell{1, 1}));
  // Nothing observed anywhere near: no escape.
  const PlanningGrid dark = test::uniform_grid(9, 9, kCellUnknown);
  EXPECT_FALSE(e.find(dark, {4, 4}, 3.0, UnknownPolicy::Blocked));
}

TEST(SegmentClearLeaving, SkipsTheImpassableCellsItStartsIn) {
  const PlanningGrid g = test::grid_from_art({"#ii.....i"});
  EXPECT_FALSE(segment_clear(g, {1.5, 0.5}, {6.5, 0.5}, UnknownPolicy::Blocked));
  EXPECT_TRUE(segment_clear_leaving(g, {1.5, 0.5}, {6.5, 0.5}, UnknownPolicy::Blocked));
  // Blocked again after leaving: not clear.
  EXPECT_FALSE(segment_clear_leaving(g, {1.5, 0.5}, {8.5, 0.5}, UnknownPolicy::Blocked));
  // Leaving may not cross a wall, though a robot may start on one (pose noise).
  const PlanningGrid walled = test::grid_from_art({"i#i....", "#i....."});
  EXPECT_FALSE(segment_clear_leaving(walled, {0.5, 1.5}, {5.5, 1.5}, UnknownPolicy::Blocked));
  EXPECT_TRUE(segment_clear_leaving(walled, {0.5, 0.5}, {5.5, 0.5}, UnknownPolicy::Blocked));
  // Never leaving is no way anywhere.
  EXPECT_FALSE(segment_clear_leaving(g, {1.2, 0.5}, {2.5, 0.5}, UnknownPolicy::Blocked));
}

TEST(PlanForRobot, StartsWithAnEscapeLegFromAnInflatedCell) {
  const PlanningGrid g = test::grid_from_art({
      "#i......",
      "#i......",
      "#i......",
  });
  PathPlanner p({});  // escape radius 0.5 m: half a cell here
  PlannerConfig wide;
  wide.escape_radius_m = 1.5;
  PathPlanner q(wide);
  const Vec2 start{1.3, 1.5};
  EXPECT_EQ(p.plan_for_robot(g, start, {6.5, 1.5}, UnknownPolicy::Blocked).status, PlanStatus::StartBlocked);
  EXPECT_FALSE(p.robot_start(g, start, UnknownPolicy::Blocked));
  const PlanResult r = q.plan_for_robot(g, start, {6.5, 1.5}, UnknownPolicy::Blocked);
  ASSERT_EQ(r.status, PlanStatus::Ok) << r.reason;
  ASSERT_GE(r.path.size(), 3u);
  EXPECT_EQ(r.path[0], start);
  EXPECT_EQ(r.path[1], (Vec2{2.5, 1.5}));
  EXPECT_EQ(r.path.back(), (Vec2{6.5, 1.5}));
  EXPECT_NEAR(r.length_m, path_length(r.path), 1e-9);
  EXPECT_EQ(q.robot_start(g, start, UnknownPolicy::Blocked), (Cell{2, 1}));
  // Path requests from clients keep the strict check.
  EXPECT_EQ(q.plan(g, {start, {6.5, 1.5}, "astar", 1.0}).status, PlanStatus::StartBlocked);
}

TEST(PlanForRobot, WalledInRobotsAndBlockedGoalsAreStillRefused) {
  const PlanningGrid g = test::grid_from_art({
      "###.....",
      "#i#..i..",
      "###.....",
  });
  PlannerConfig c;
  c.escape_radius_m = 2.0;
  PathPlanner p(c);
  const PlanResult walled = p.plan_for_robot(g, {1.5, 1.5}, {6.5, 1.5}, UnknownPolicy::Blocked);
  EXPECT_EQ(walled.status, PlanStatus::StartBlocked);
  EXPECT_NE(walled.reason.find("no passable cell within"), std::string::npos) << walled.reason;
  EXPECT_EQ(p.plan_for_robot(g, {3.5, 1.5}, {5.5, 1.5}, UnknownPolicy::Blocked).status,
            PlanStatus::GoalBlocked);
  // Home snaps to a passable cell beside it.
  const PlanResult home = p.plan_for_robot(g, {3.5, 1.5}, {5.5, 1.5}, UnknownPolicy::Blocked, true);
  ASSERT_EQ(home.status, PlanStatus::Ok) << home.reason;
  EXPECT_EQ(distance(home.path.back(), {5.5, 1.5}), 1.0);
}

TEST(PlanForRobot, ValidatesTheEscapeRadius) {
  PlannerConfig c;
  c.escape_radius_m = -1.0;
  EXPECT_FALSE(validate(c));
  c.escape_radius_m = 0.0;
  EXPECT_TRUE(validate(c));
}

}  // namespace
}  // namespace slam::planner
