// The "Set pose" tool: press at the robot's true position, drag towards its heading, release ->
// the InitialPose values; Escape / right click cancel; nothing without one selected robot. And the
// map-level actions: window points become map points, the send is tracked until the mapper replies.
#include "viewer/core/pose_tool.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fake_command_sink.hpp"
#include "viewer/core/clicks_tab.hpp"

namespace slam::viewer {
namespace {

TEST(PoseTool, PressDragReleaseGivesThePressedPointAndTheDragHeading) {
  PoseTool tool;
  ASSERT_TRUE(tool.arm("r1"));
  tool.press({2.0, 1.0});
  EXPECT_TRUE(tool.dragging());
  tool.drag({2.0, 3.0});
  ASSERT_TRUE(tool.arrow());
  EXPECT_DOUBLE_EQ(tool.arrow()->from.x, 2.0);
  EXPECT_DOUBLE_EQ(tool.arrow()->to.y, 3.0);
  const auto pose = tool.release({1.0, 2.0}, 0.1);  // released up and to the left of the press
  ASSERT_TRUE(pose);
  EXPECT_EQ(pose->robot_id, "r1");
  EXPECT_DOUBLE_EQ(pose->pose.x, 2.0);
  EXPECT_DOUBLE_EQ(pose->pose.y, 1.0);
  EXPECT_NEAR(pose->pose.theta, 3.0 * std::numbers::pi / 4.0, 1e-12);
  EXPECT_FALSE(tool.armed());  // one use
  EXPECT_FALSE(tool.arrow());
}

TEST(PoseTool, NeedsOneSelectedRobot) {
  PoseTool tool;
  EXPECT_FALSE(tool.arm("*"));
  EXPECT_FALSE(tool.arm(""));
  EXPECT_FALSE(tool.armed());
  tool.press({1.0, 1.0});
  EXPECT_FALSE(tool.dragging());
  EXPECT_FALSE(tool.release({2.0, 1.0}, 0.1));
}

TEST(PoseTool, TooShortADragGivesNoHeadingAndStaysArmed) {
  PoseTool tool;
  ASSERT_TRUE(tool.arm("r1"));
  tool.press({1.0, 1.0});
  EXPECT_FALSE(tool.release({1.05, 1.0}, 0.1));
  EXPECT_TRUE(tool.armed());
  EXPECT_FALSE(tool.dragging());
}

TEST(PoseTool, CancelDropsTheDragAndDisarms) {
  PoseTool tool;
  ASSERT_TRUE(tool.arm("r1"));
  tool.press({1.0, 1.0});
  tool.cancel();
  EXPECT_FALSE(tool.armed());
  EXPECT_FALSE(tool.arrow());
  EXPECT_FALSE(tool.release({3.0, 1.0}, 0.1));
}

class PoseToolOnMap : public ::testing::Test {
 protected:
  PoseToolOnMap() {
    state.view.set_viewport({0.0, 0.0, 400.0, 400.0});
    state.view.fit({-10.0, -10.0, 10.0, 10.0});
  }
  ViewerState state{100};
  FakeCommandSink sink;
};

TEST_F(PoseToolOnMap, ReleaseSendsInitialPoseAtTheWorldPointsAndTracksTheReply) {
  state.selected_robot = "r2";
  arm_pose_tool(state);
  ASSERT_TRUE(state.pose_tool.armed());
  const Vec2 press{200.0, 200.0}, release{260.0, 200.0};  // drag to the right on screen: heading 0
  pose_press(state, press);
  pose_drag(state, {230.0, 200.0});
  pose_release(state, sink, release, 1000);
  ASSERT_EQ(sink.initial_poses.size(), 1u);
  const InitialPoseCommand& c = sink.initial_poses[0];
  const Vec2 at = state.view.screen_to_world(press);
  EXPECT_EQ(c.robot_id, "r2");
  EXPECT_DOUBLE_EQ(c.pose.x, at.x);
  EXPECT_DOUBLE_EQ(c.pose.y, at.y);
  EXPECT_NEAR(c.pose.theta, 0.0, 1e-12);
  ASSERT_TRUE(state.pose_requests.last());
  EXPECT_EQ(state.pose_requests.last()->state, RequestState::Waiting);

  // The mapper's MapReply with that request id settles it.
  IntakeBatch batch;
  batch.replies.push_back({sink.last_id, 1, "robot 'r2' unknown"});
  state.ingest(batch, 2000);
  EXPECT_EQ(state.pose_requests.last()->state, RequestState::Failed);
  EXPECT_EQ(state.pose_requests.last()->message, "robot 'r2' unknown");
}

TEST_F(PoseToolOnMap, EveryRobotSelectedRefusesToArm) {
  state.selected_robot.assign(
      1, '*');  // "*": every robot (assign(count, char) sidesteps a GCC 12 -Wrestrict false positive)
  arm_pose_tool(state);
  EXPECT_FALSE(state.pose_tool.armed());
  EXPECT_NE(state.status_line.find("select one robot"), std::string::npos);
}

TEST_F(PoseToolOnMap, CancelSendsNothing) {
  state.selected_robot = "r1";
  arm_pose_tool(state);
  pose_press(state, {200.0, 200.0});
  cancel_pose_tool(state);
  pose_release(state, sink, {260.0, 200.0}, 1000);
  EXPECT_EQ(sink.total(), 0u);
  EXPECT_FALSE(state.pose_tool.armed());
}

TEST_F(PoseToolOnMap, RefusedSendShowsAnError) {
  state.selected_robot = "r1";
  sink.refuse = true;
  arm_pose_tool(state);
  pose_press(state, {200.0, 200.0});
  pose_release(state, sink, {200.0, 140.0}, 1000);
  EXPECT_NE(state.status_line.find("NOT sent"), std::string::npos);
  EXPECT_FALSE(state.pose_requests.last());
}

}  // namespace
}  // namespace slam::viewer
