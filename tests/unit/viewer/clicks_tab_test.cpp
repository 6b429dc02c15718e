// Clicks tab and map clicks: each button's action is set separately, and a click sends the
// command its action asks for at the world point under the cursor (nothing for "nothing").
#include "viewer/core/clicks_tab.hpp"

#include <gtest/gtest.h>

#include "fake_command_sink.hpp"

namespace slam::viewer {
namespace {

class ClicksTabTest : public ::testing::Test {
 protected:
  ClicksTabTest() {
    state.view.set_viewport({0.0, 0.0, 400.0, 400.0});
    state.view.fit({-10.0, -10.0, 10.0, 10.0});
  }
  ViewerState state{100};
  FakeCommandSink sink;
  const Vec2 screen{300.0, 100.0};
};

TEST_F(ClicksTabTest, EachButtonHasItsOwnAction) {
  set_click_action(state, MouseButton::Left, ClickAction::Unobstruct);
  set_click_action(state, MouseButton::Right, ClickAction::Nothing);
  EXPECT_EQ(state.left_click, ClickAction::Unobstruct);
  EXPECT_EQ(state.right_click, ClickAction::Nothing);
}

TEST_F(ClicksTabTest, LeftClickSetsTheTargetOfTheSelectedRobot) {
  state.selected_robot = "r1";
  apply_click(state, sink, screen, MouseButton::Left);  // default left action: set target
  ASSERT_EQ(sink.goals.size(), 1u);
  const Vec2 w = state.view.screen_to_world(screen);
  EXPECT_EQ(sink.goals[0].robot_id, "r1");
  EXPECT_DOUBLE_EQ(sink.goals[0].target.x, w.x);
  EXPECT_DOUBLE_EQ(sink.goals[0].target.y, w.y);
  EXPECT_GT(w.x, 0.0);  // right half of the view
  EXPECT_GT(w.y, 0.0);  // upper half (y up)
  EXPECT_NE(state.status_line.find("goal for r1"), std::string::npos);
}

TEST_F(ClicksTabTest, TargetUsesTheRobotsModeAndSquareSettings) {
  msg::RobotState s;
  s.robot_id = "r1";
  state.robots.ingest(std::move(s));
  state.robots.find("r1")->settings.mode = GoalMode::Square;
  state.selected_robot = "r1";
  state.square_size = 2.0;
  state.square_centred = true;
  apply_click(state, sink, screen, MouseButton::Left);
  ASSERT_EQ(sink.goals.size(), 1u);
  EXPECT_EQ(sink.goals[0].mode, GoalMode::Square);
  EXPECT_DOUBLE_EQ(sink.goals[0].square_size, 2.0);
  EXPECT_TRUE(sink.goals[0].square_centred);
}

TEST_F(ClicksTabTest, RightClickObstructsByDefault) {
  apply_click(state, sink, screen, MouseButton::Right);
  ASSERT_EQ(sink.edits.size(), 1u);
  EXPECT_EQ(sink.edits[0].kind, MapEditKind::Obstruct);
  EXPECT_DOUBLE_EQ(sink.edits[0].point.x, state.view.screen_to_world(screen).x);
  EXPECT_TRUE(sink.goals.empty());
}

TEST_F(ClicksTabTest, UnobstructAction) {
  set_click_action(state, MouseButton::Right, ClickAction::Unobstruct);
  apply_click(state, sink, screen, MouseButton::Right);
  ASSERT_EQ(sink.edits.size(), 1u);
  EXPECT_EQ(sink.edits[0].kind, MapEditKind::Unobstruct);
}

TEST_F(ClicksTabTest, NothingSendsNothing) {
  set_click_action(state, MouseButton::Left, ClickAction::Nothing);
  apply_click(state, sink, screen, MouseButton::Left);
  EXPECT_EQ(sink.total(), 0u);
}

TEST_F(ClicksTabTest, RefusedClickSaysSoOnTheStatusLine) {
  sink.refuse = true;
  apply_click(state, sink, screen, MouseButton::Right);
  EXPECT_NE(state.status_line.find("NOT sent"), std::string::npos);
}

}  // namespace
}  // namespace slam::viewer
