// Drive tab goals: the corner buttons send the selected robot (or every robot) to the square's
// corners as the planner drives them; the other buttons carry the target and square settings.
#include "viewer/core/drive_goals.hpp"

#include <gtest/gtest.h>

#include "common/core/square_path.hpp"

namespace slam::viewer {
namespace {

void expect_at(const Vec2& got, double x, double y) {
  EXPECT_DOUBLE_EQ(got.x, x);
  EXPECT_DOUBLE_EQ(got.y, y);
}

TEST(DriveGoals, CornerButtonsSendEachCornerToTheSelectedRobot) {
  const DriveSettings s{"r7", {-1.5, 0.25}, 3.0, true};
  const auto corners = square_corners(s.target, s.square_size, s.square_centred);
  for (bool planned : {false, true}) {
    const auto goals = corner_goals(s, planned);
    for (size_t i = 0; i < 4; ++i) {
      SCOPED_TRACE(i);
      EXPECT_EQ(goals[i].robot_id, "r7");
      EXPECT_EQ(goals[i].mode, planned ? GoalMode::Planned : GoalMode::Direct);
      EXPECT_EQ(goals[i].target.x, corners[i].x);  // exactly the planner's corner, not just close
      EXPECT_EQ(goals[i].target.y, corners[i].y);
    }
  }
  expect_at(corner_goals(s, false)[0].target, -3.0, -1.25);
  expect_at(corner_goals(s, false)[2].target, 0.0, 1.75);
}

TEST(DriveGoals, EveryRobotWhenAllIsSelected) {
  const DriveSettings s{"*", {0.0, 0.0}, 1.0, false};
  for (const GoalCommand& g : corner_goals(s, true)) EXPECT_EQ(g.robot_id, "*");
  EXPECT_EQ(drive_goal(s, GoalMode::Direct).robot_id, "*");
}

TEST(DriveGoals, TargetAndSquareButtonsCarryTheSettings) {
  const DriveSettings s{"r1", {4.0, -2.0}, 2.5, true};
  const GoalCommand square = drive_goal(s, GoalMode::Square);
  EXPECT_EQ(square.mode, GoalMode::Square);
  expect_at(square.target, 4.0, -2.0);
  EXPECT_DOUBLE_EQ(square.square_size, 2.5);
  EXPECT_TRUE(square.square_centred);
  const GoalCommand planned = drive_goal(s, GoalMode::Planned);
  EXPECT_EQ(planned.mode, GoalMode::Planned);
  expect_at(planned.target, 4.0, -2.0);
  EXPECT_EQ(drive_goal(s, GoalMode::Stop).mode, GoalMode::Stop);
}

TEST(DriveGoals, DescriptionsNameWhatAndWhom) {
  EXPECT_EQ(describe(corner_goals({"*", {1.0, 2.0}, 1.0, false}, true)[1]),
            "planned goal to (2.00, 2.00) for every robot");
  EXPECT_EQ(describe(drive_goal({"r1", {1.0, 2.0}, 2.0, true}, GoalMode::Square)),
            "square goal (2.00 m, centred on (1.00, 2.00)) for r1");
  EXPECT_EQ(describe(drive_goal({"r1", {1.0, 2.0}, 2.0, false}, GoalMode::Square)),
            "square goal (2.00 m, first corner at (1.00, 2.00)) for r1");
  EXPECT_EQ(describe(drive_goal({"r2", {}, 1.0, false}, GoalMode::Home)), "home goal for r2");
}

}  // namespace
}  // namespace slam::viewer
