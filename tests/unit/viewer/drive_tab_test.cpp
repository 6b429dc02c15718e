// DriveTab: every Drive button sends its goal to the selected robot or every robot, the target
// can be taken from the selected robot, the square's side is bounded, corners follow the
// direct/planned choice, and a non-finite target is refused.
#include "viewer/core/drive_tab.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "fake_command_sink.hpp"

namespace slam::viewer {
namespace {

class DriveTabTest : public ::testing::Test {
 protected:
  void add_robot(const std::string& id, double x, double y) {
    msg::RobotState s;
    s.robot_id = id;
    s.pose = {x, y, 0.0};
    state.robots.ingest(std::move(s));
  }
  ViewerState state{100};
  FakeCommandSink sink;
  DriveTab tab;
};

TEST_F(DriveTabTest, EveryModeButtonSendsItsGoalToTheSelection) {
  state.selected_robot = "r1";
  tab.target = {2.0, 3.0};
  for (GoalMode mode : {GoalMode::Direct, GoalMode::Planned, GoalMode::Square, GoalMode::Stop, GoalMode::Home,
                        GoalMode::Explore, GoalMode::Idle})
    tab.drive(state, sink, mode);
  ASSERT_EQ(sink.goals.size(), 7u);
  EXPECT_EQ(sink.goals[0].mode, GoalMode::Direct);
  EXPECT_EQ(sink.goals[1].mode, GoalMode::Planned);
  EXPECT_EQ(sink.goals[2].mode, GoalMode::Square);
  EXPECT_EQ(sink.goals[3].mode, GoalMode::Stop);
  EXPECT_EQ(sink.goals[4].mode, GoalMode::Home);
  EXPECT_EQ(sink.goals[5].mode, GoalMode::Explore);
  EXPECT_EQ(sink.goals[6].mode, GoalMode::Idle);
  for (const GoalCommand& g : sink.goals) {
    EXPECT_EQ(g.robot_id, "r1");
    EXPECT_DOUBLE_EQ(g.target.x, 2.0);
    EXPECT_DOUBLE_EQ(g.target.y, 3.0);
  }
  EXPECT_EQ(state.status_line, "idle goal for r1 (request 7)");
}

TEST_F(DriveTabTest, EveryRobotByDefault) {
  tab.drive(state, sink, GoalMode::Stop);
  ASSERT_EQ(sink.goals.size(), 1u);
  EXPECT_EQ(sink.goals[0].robot_id, "*");
}

TEST_F(DriveTabTest, SquareCarriesSideAndAnchor) {
  DriveTab::set_square_side(state, 2.5);
  DriveTab::set_square_centred(state, true);
  tab.drive(state, sink, GoalMode::Square);
  ASSERT_EQ(sink.goals.size(), 1u);
  EXPECT_DOUBLE_EQ(sink.goals[0].square_size, 2.5);
  EXPECT_TRUE(sink.goals[0].square_centred);
}

TEST_F(DriveTabTest, SquareSideIsAtLeastTheMinimumAndIgnoresNonFinite) {
  DriveTab::set_square_side(state, 0.01);
  EXPECT_DOUBLE_EQ(state.square_size, kMinSquareSide);
  DriveTab::set_square_side(state, -3.0);
  EXPECT_DOUBLE_EQ(state.square_size, kMinSquareSide);
  DriveTab::set_square_side(state, 2.0);
  DriveTab::set_square_side(state, std::nan(""));
  EXPECT_DOUBLE_EQ(state.square_size, 2.0);
}

TEST_F(DriveTabTest, CornersSendDirectOrPlannedGoalsToEachCorner) {
  tab.target = {1.0, 1.0};
  DriveTab::set_square_side(state, 2.0);
  for (size_t i = 0; i < 4; ++i) tab.drive_corner(state, sink, i);
  tab.planned_corners = true;
  tab.drive_corner(state, sink, 2);
  ASSERT_EQ(sink.goals.size(), 5u);
  const std::array<GoalCommand, 4> want = corner_goals(tab.settings(state), false);
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(sink.goals[i].mode, GoalMode::Direct);
    EXPECT_DOUBLE_EQ(sink.goals[i].target.x, want[i].target.x);
    EXPECT_DOUBLE_EQ(sink.goals[i].target.y, want[i].target.y);
  }
  EXPECT_DOUBLE_EQ(sink.goals[2].target.x, 3.0);  // first corner at the target, +x +y
  EXPECT_DOUBLE_EQ(sink.goals[2].target.y, 3.0);
  EXPECT_EQ(sink.goals[4].mode, GoalMode::Planned);
  EXPECT_DOUBLE_EQ(sink.goals[4].target.x, 3.0);
}

TEST_F(DriveTabTest, CornerOutOfRangeIsRefused) {
  tab.drive_corner(state, sink, 4);
  EXPECT_EQ(sink.total(), 0u);
  EXPECT_FALSE(tab.error.empty());
}

TEST_F(DriveTabTest, NonFiniteTargetIsRefused) {
  tab.target = {std::nan(""), 0.0};
  tab.drive(state, sink, GoalMode::Direct);
  tab.target = {0.0, INFINITY};
  tab.drive(state, sink, GoalMode::Planned);
  EXPECT_EQ(sink.total(), 0u);
  EXPECT_FALSE(tab.error.empty());
}

TEST_F(DriveTabTest, UseRobotPositionCopiesTheSelectedRobotsPose) {
  add_robot("r1", 4.5, -1.5);
  state.selected_robot = "r1";
  tab.use_robot_position(state);
  EXPECT_DOUBLE_EQ(tab.target.x, 4.5);
  EXPECT_DOUBLE_EQ(tab.target.y, -1.5);
  EXPECT_TRUE(tab.error.empty());
}

TEST_F(DriveTabTest, UseRobotPositionNeedsOneKnownRobot) {
  tab.target = {1.0, 1.0};
  tab.use_robot_position(state);  // "*": every robot
  EXPECT_FALSE(tab.error.empty());
  state.selected_robot = "unknown";
  tab.use_robot_position(state);
  EXPECT_FALSE(tab.error.empty());
  EXPECT_DOUBLE_EQ(tab.target.x, 1.0);
  EXPECT_EQ(sink.total(), 0u);
}

TEST_F(DriveTabTest, RefusedSendShowsAnError) {
  sink.refuse = true;
  tab.drive(state, sink, GoalMode::Home);
  EXPECT_NE(tab.error.find("NOT sent"), std::string::npos);
}

}  // namespace
}  // namespace slam::viewer
