// RobotsTab: the default mode goes to every robot, a robot's own mode to it (towards its target
// or position), reset deletes its observations and the points kept here, select, defaults,
// "last N" and the id filter.
#include "viewer/core/robots_tab.hpp"

#include <gtest/gtest.h>

#include "fake_command_sink.hpp"

namespace slam::viewer {
namespace {

class RobotsTabTest : public ::testing::Test {
 protected:
  RobotView& add_robot(const std::string& id, double x, double y) {
    msg::RobotState s;
    s.robot_id = id;
    s.pose = {x, y, 0.0};
    state.robots.ingest(std::move(s));
    return *state.robots.find(id);
  }
  ViewerState state{100};
  FakeCommandSink sink;
  RobotsTab tab;
};

TEST_F(RobotsTabTest, SendToAllUsesTheDefaultModeAndSquare) {
  state.robots.defaults().mode = GoalMode::Explore;
  state.square_size = 3.0;
  tab.send_default_mode(state, sink);
  ASSERT_EQ(sink.goals.size(), 1u);
  EXPECT_EQ(sink.goals[0].robot_id, "*");
  EXPECT_EQ(sink.goals[0].mode, GoalMode::Explore);
  EXPECT_DOUBLE_EQ(sink.goals[0].square_size, 3.0);
  EXPECT_NE(state.status_line.find("explore goal for every robot"), std::string::npos);
}

TEST_F(RobotsTabTest, RobotModeGoesToItsPositionWithoutAPath) {
  RobotView& r = add_robot("r1", 1.0, 2.0);
  r.settings.mode = GoalMode::Home;
  tab.send_robot_mode(state, sink, r);
  ASSERT_EQ(sink.goals.size(), 1u);
  EXPECT_EQ(sink.goals[0].robot_id, "r1");
  EXPECT_EQ(sink.goals[0].mode, GoalMode::Home);
  EXPECT_DOUBLE_EQ(sink.goals[0].target.x, 1.0);
  EXPECT_DOUBLE_EQ(sink.goals[0].target.y, 2.0);
}

TEST_F(RobotsTabTest, RobotModeKeepsItsCurrentTarget) {
  RobotView& r = add_robot("r1", 1.0, 2.0);
  msg::RobotPath p;
  p.robot_id = "r1";
  p.target = {7.0, 8.0};
  state.robots.ingest(std::move(p));
  r.settings.mode = GoalMode::Planned;
  tab.send_robot_mode(state, sink, r);
  ASSERT_EQ(sink.goals.size(), 1u);
  EXPECT_DOUBLE_EQ(sink.goals[0].target.x, 7.0);
  EXPECT_EQ(sink.goals[0].mode, GoalMode::Planned);
}

TEST_F(RobotsTabTest, ResetSendsItsMapEditAndDropsThePointsHere) {
  RobotView& r = add_robot("r1", 0.0, 0.0);
  state.robots.ingest(ObservationData{"r1", 1, {}, {1.0f, 2.0f, 3.0f, 4.0f}});
  ASSERT_EQ(r.points.size(), 2u);
  tab.reset_robot(state, sink, r);
  ASSERT_EQ(sink.edits.size(), 1u);
  EXPECT_EQ(sink.edits[0].kind, MapEditKind::ResetRobot);
  EXPECT_EQ(sink.edits[0].robot_id, "r1");
  EXPECT_EQ(r.points.size(), 0u);
}

TEST_F(RobotsTabTest, RefusedResetKeepsThePointsAndShowsAnError) {
  RobotView& r = add_robot("r1", 0.0, 0.0);
  state.robots.ingest(ObservationData{"r1", 1, {}, {1.0f, 2.0f}});
  sink.refuse = true;
  tab.reset_robot(state, sink, r);
  EXPECT_EQ(r.points.size(), 1u);
  EXPECT_NE(tab.error.find("NOT sent"), std::string::npos);
}

TEST_F(RobotsTabTest, AnswersToAPlacementGoToTheMapper) {
  const RobotView& r = add_robot("r1", 0.0, 0.0);
  tab.answer_placement(state, sink, r, true);
  tab.answer_placement(state, sink, r, false);
  ASSERT_EQ(sink.placement_answers.size(), 2u);
  EXPECT_EQ(sink.placement_answers[0].robot_id, "r1");
  EXPECT_TRUE(sink.placement_answers[0].accept);
  EXPECT_FALSE(sink.placement_answers[1].accept);
  sink.refuse = true;
  tab.answer_placement(state, sink, r, true);
  EXPECT_NE(tab.error.find("NOT sent"), std::string::npos);
}

TEST_F(RobotsTabTest, SelectChoosesWhereGoalsGo) {
  RobotsTab::select(state, "r2");
  EXPECT_EQ(state.selected_robot, "r2");
  RobotsTab::select(state, "*");
  EXPECT_EQ(state.selected_robot, "*");
}

TEST_F(RobotsTabTest, ApplyDefaultsReachesEveryRobot) {
  RobotView& a = add_robot("a", 0.0, 0.0);
  RobotView& b = add_robot("b", 0.0, 0.0);
  state.robots.defaults().size_m = 1.5f;
  RobotsTab::apply_defaults(state);
  EXPECT_FLOAT_EQ(a.settings.size_m, 1.5f);
  EXPECT_FLOAT_EQ(b.settings.size_m, 1.5f);
}

TEST_F(RobotsTabTest, LastNIsNeverNegative) {
  RobotSettings s;
  RobotsTab::set_last_n(s, 500);
  EXPECT_EQ(s.last_n, 500u);
  RobotsTab::set_last_n(s, -100);
  EXPECT_EQ(s.last_n, 0u);
}

TEST_F(RobotsTabTest, FilterMatchesIdSubstrings) {
  const RobotView& r = add_robot("sim-12", 0.0, 0.0);
  EXPECT_TRUE(tab.shows(r));
  tab.filter = "m-1";
  EXPECT_TRUE(tab.shows(r));
  tab.filter = "alpha";
  EXPECT_FALSE(tab.shows(r));
}

}  // namespace
}  // namespace slam::viewer
