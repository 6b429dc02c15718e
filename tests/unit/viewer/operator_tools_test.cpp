// The viewer's operator tools without GL or DDS: the alerts board, forgetting a robot (the button
// sends the command; the command coming back drops the robot) and the path preview's two clicks,
// its request and the reply it keeps (length, or the reason it failed).
#include <gtest/gtest.h>

#include "fake_command_sink.hpp"
#include "viewer/core/alert_board.hpp"
#include "viewer/core/path_preview.hpp"
#include "viewer/core/preview_clicks.hpp"
#include "viewer/core/robots_tab.hpp"
#include "viewer/core/viewer_state.hpp"

namespace slam::viewer {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

msg::Alert alert(const std::string& id, bool active, int64_t raised_s) {
  return {id,
          AlertKind::BatteryLow,
          "r1",
          active,
          raised_s * kSecond,
          raised_s * kSecond,
          "robot 'r1' battery 10 %",
          "host:1"};
}

TEST(AlertBoard, KeepsTheLatestStatePerAlertAndListsActiveNewestFirst) {
  AlertBoard board;
  board.update(alert("battery/r1", true, 10));
  board.update(alert("offline/r1", true, 20));
  board.update(alert("silent/x", true, 5));
  board.update(alert("silent/x", false, 5));  // cleared
  const auto active = board.active();
  ASSERT_EQ(active.size(), 2u);
  EXPECT_EQ(board.active_count(), 2u);
  EXPECT_EQ(active[0]->alert_id, "offline/r1");
  EXPECT_EQ(active[1]->alert_id, "battery/r1");
  const std::string line = describe(*active[1], 25 * kSecond);
  EXPECT_NE(line.find("battery low"), std::string::npos) << line;
  EXPECT_NE(line.find("15 s ago"), std::string::npos) << line;
  EXPECT_NE(line.find("battery 10 %"), std::string::npos) << line;
}

TEST(RobotRegistry, ForgetRemovesOneRobotAndKeepsTheOthersFindable) {
  RobotRegistry robots;
  for (const char* id : {"a", "b", "c"}) robots.get_or_add(id);
  EXPECT_TRUE(robots.forget("a"));
  EXPECT_FALSE(robots.forget("a"));
  EXPECT_EQ(robots.removals(), 1u) << "positions moved: position-keyed data must be rebuilt";
  EXPECT_EQ(robots.size(), 2u);
  EXPECT_EQ(robots.find("a"), nullptr);
  ASSERT_NE(robots.find("b"), nullptr);
  EXPECT_EQ(robots.find("b")->id, "b");
  ASSERT_NE(robots.find("c"), nullptr);
  EXPECT_EQ(robots.find("c")->id, "c");
}

TEST(ForgetRobot, ButtonSendsTheCommandAndItsEchoDropsTheRobot) {
  ViewerState state{100};
  FakeCommandSink sink;
  RobotsTab tab;
  msg::RobotState s;
  s.robot_id = "r1";
  IntakeBatch batch;
  batch.states.push_back(s);
  state.ingest(batch, 0);
  state.selected_robot = "r1";
  tab.forget_robot(state, sink, *state.robots.find("r1"));
  ASSERT_EQ(sink.forgets.size(), 1u);
  EXPECT_EQ(sink.forgets[0].robot_id, "r1");
  EXPECT_NE(state.robots.find("r1"), nullptr) << "dropped only when the command comes back";

  batch.clear();
  batch.forgets.push_back({"r1"});
  state.ingest(batch, 0);
  EXPECT_EQ(state.robots.find("r1"), nullptr);
  EXPECT_EQ(state.selected_robot, "*");

  sink.refuse = true;
  state.robots.get_or_add("r2");
  tab.forget_robot(state, sink, *state.robots.find("r2"));
  EXPECT_NE(tab.error.find("NOT sent"), std::string::npos) << tab.error;
}

class PathPreviewTest : public ::testing::Test {
 protected:
  PathPreviewTest() {
    state.view.set_viewport({0.0, 0.0, 400.0, 400.0});
    state.view.fit({-10.0, -10.0, 10.0, 10.0});
  }
  ViewerState state{100};
  FakeCommandSink sink;
};

TEST_F(PathPreviewTest, TwoClicksSendOneRequestAndItsReplyIsKept) {
  path_preview_click(state, sink, {100, 100}, 0);  // not armed: nothing
  EXPECT_TRUE(sink.path_previews.empty());
  arm_path_preview(state);
  EXPECT_TRUE(state.path_preview.armed());
  path_preview_click(state, sink, {100, 300}, 0);
  EXPECT_TRUE(sink.path_previews.empty());
  ASSERT_TRUE(state.path_preview.pending_start());
  EXPECT_NE(state.path_preview.summary().find("goal"), std::string::npos);
  path_preview_click(state, sink, {300, 100}, 0);
  ASSERT_EQ(sink.path_previews.size(), 1u);
  EXPECT_FALSE(state.path_preview.armed());
  const PathPreviewCommand& sent = sink.path_previews[0];
  EXPECT_LT(sent.start.x, 0.0);
  EXPECT_GT(sent.goal.x, 0.0);
  EXPECT_EQ(sent.algorithm, "astar");
  EXPECT_NE(state.path_preview.summary().find("waiting"), std::string::npos);

  IntakeBatch batch;
  batch.path_replies.push_back(
      {sink.last_id + 7, msg::PlanStatus::Ok, "", {{0, 0}, {1, 1}}, 99.0, 0.01});  // another's
  batch.path_replies.push_back(
      {sink.last_id, msg::PlanStatus::Ok, "", {sent.start, {0, 0}, sent.goal}, 12.5, 0.004});
  state.ingest(batch, kSecond);
  ASSERT_TRUE(state.path_preview.result());
  EXPECT_EQ(state.path_preview.result()->path.size(), 3u);
  EXPECT_NE(state.path_preview.summary().find("12.50 m"), std::string::npos) << state.path_preview.summary();
  EXPECT_NE(state.path_preview.summary().find("3 points"), std::string::npos) << state.path_preview.summary();
}

TEST_F(PathPreviewTest, AFailedRequestShowsItsReason) {
  arm_path_preview(state);
  path_preview_click(state, sink, {100, 300}, 0);
  path_preview_click(state, sink, {300, 100}, 0);
  IntakeBatch batch;
  batch.path_replies.push_back(
      {sink.last_id, msg::PlanStatus::GoalBlocked, "goal is inside an obstacle", {}, 0.0, 0.001});
  state.ingest(batch, kSecond);
  ASSERT_TRUE(state.path_preview.result());
  EXPECT_EQ(state.path_preview.result()->status, msg::PlanStatus::GoalBlocked);
  EXPECT_EQ(state.path_preview.summary(), "no path: goal is inside an obstacle");
}

TEST_F(PathPreviewTest, NoReplyAndRefusalAreSaid) {
  arm_path_preview(state);
  path_preview_click(state, sink, {100, 300}, 0);
  path_preview_click(state, sink, {300, 100}, 0);
  IntakeBatch batch;
  state.ingest(batch, 10 * kSecond);
  EXPECT_NE(state.path_preview.summary().find("no reply"), std::string::npos) << state.path_preview.summary();

  sink.refuse = true;
  arm_path_preview(state);
  path_preview_click(state, sink, {100, 300}, 0);
  path_preview_click(state, sink, {300, 100}, 0);
  EXPECT_NE(state.path_preview.summary().find("NOT sent"), std::string::npos) << state.path_preview.summary();
}

TEST_F(PathPreviewTest, CancelDisarms) {
  arm_path_preview(state);
  path_preview_click(state, sink, {100, 300}, 0);
  cancel_path_preview(state);
  EXPECT_FALSE(state.path_preview.armed());
  path_preview_click(state, sink, {300, 100}, 0);
  EXPECT_TRUE(sink.path_previews.empty());
}

}  // namespace
}  // namespace slam::viewer
