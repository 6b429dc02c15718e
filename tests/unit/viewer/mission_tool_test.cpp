// The mission tool: armed, left clicks add waypoints (right clicks keep their action); Send gives
// the selected robot the draft, looped or once, and refuses what cannot run; Undo and Clear edit
// the draft. Received missions: the one further along is kept whatever order samples arrive in.
#include "viewer/core/mission_tool.hpp"

#include <gtest/gtest.h>

#include "fake_command_sink.hpp"
#include "viewer/core/clicks_tab.hpp"

namespace slam::viewer {
namespace {

class MissionToolTest : public ::testing::Test {
 protected:
  MissionToolTest() {
    state.view.set_viewport({0.0, 0.0, 400.0, 400.0});
    state.view.fit({-10.0, -10.0, 10.0, 10.0});
    state.selected_robot = "r1";
  }
  ViewerState state{100};
  FakeCommandSink sink;
};

TEST_F(MissionToolTest, ArmedLeftClicksAddWaypointsInsteadOfGoals) {
  state.mission_tool.set_armed(true);
  apply_click(state, sink, {300.0, 100.0}, MouseButton::Left);
  apply_click(state, sink, {100.0, 300.0}, MouseButton::Left);
  EXPECT_TRUE(sink.goals.empty());
  ASSERT_EQ(state.mission_tool.waypoints().size(), 2u);
  EXPECT_EQ(state.mission_tool.waypoints()[0], state.view.screen_to_world({300.0, 100.0}));
  EXPECT_NE(state.status_line.find("mission waypoint 2"), std::string::npos) << state.status_line;
  // The right button keeps its own action.
  apply_click(state, sink, {200.0, 200.0}, MouseButton::Right);
  EXPECT_EQ(sink.edits.size(), 1u);
  EXPECT_EQ(state.mission_tool.waypoints().size(), 2u);
  // Disarmed, a left click is a goal again.
  state.mission_tool.set_armed(false);
  apply_click(state, sink, {300.0, 100.0}, MouseButton::Left);
  EXPECT_EQ(sink.goals.size(), 1u);
}

TEST_F(MissionToolTest, SendGivesTheSelectedRobotTheDraft) {
  ASSERT_TRUE(state.mission_tool.add({1, 2}));
  ASSERT_TRUE(state.mission_tool.add({3, 4}));
  state.mission_tool.set_loop(true);
  send_mission(state, sink);
  ASSERT_EQ(sink.missions.size(), 1u);
  EXPECT_EQ(sink.missions[0].robot_id, "r1");
  EXPECT_EQ(sink.missions[0].waypoints, (std::vector<Vec2>{{1, 2}, {3, 4}}));
  EXPECT_TRUE(sink.missions[0].loop);
  EXPECT_NE(state.status_line.find("mission of 2 waypoint(s), looped, for r1"), std::string::npos)
      << state.status_line;
  EXPECT_EQ(state.mission_tool.waypoints().size(), 2u) << "kept to adjust and send again";

  sink.refuse = true;
  send_mission(state, sink);
  EXPECT_NE(state.status_line.find("NOT sent"), std::string::npos) << state.status_line;
}

TEST_F(MissionToolTest, SendRefusesWhatCannotRun) {
  send_mission(state, sink);
  EXPECT_EQ(state.status_line, "click on the map to add waypoints first");
  ASSERT_TRUE(state.mission_tool.add({1, 2}));
  state.mission_tool.set_loop(true);
  send_mission(state, sink);
  EXPECT_EQ(state.status_line, "a looped mission needs at least two waypoints");
  ASSERT_TRUE(state.mission_tool.add({3, 4}));
  state.selected_robot = "*";
  send_mission(state, sink);
  EXPECT_EQ(state.status_line, "select one robot for the mission");
  EXPECT_TRUE(sink.missions.empty());
}

TEST_F(MissionToolTest, UndoAndClearEditTheDraftWhichHasABound) {
  MissionTool tool;
  tool.undo();  // nothing to undo: no harm
  ASSERT_TRUE(tool.add({1, 1}));
  ASSERT_TRUE(tool.add({2, 2}));
  tool.undo();
  EXPECT_EQ(tool.waypoints(), (std::vector<Vec2>{{1, 1}}));
  tool.clear();
  EXPECT_TRUE(tool.waypoints().empty());
  for (size_t i = 0; i < kMaxMissionWaypoints; ++i) ASSERT_TRUE(tool.add({0, 0}));
  EXPECT_FALSE(tool.add({0, 0}));
  EXPECT_EQ(tool.waypoints().size(), kMaxMissionWaypoints);
}

msg::Mission mission(uint64_t id, uint32_t current, uint32_t laps,
                     MissionStatus status = MissionStatus::Active) {
  msg::Mission m;
  m.robot_id = "r1";
  m.mission_id = id;
  m.waypoints = {{0, 0}, {1, 0}, {1, 1}};
  m.loop = true;
  m.current = current;
  m.laps = laps;
  m.status = status;
  return m;
}

TEST(RobotRegistryMissions, KeepsTheSampleFurtherAlongOfTheSameMission) {
  RobotRegistry robots;
  robots.ingest(mission(5, 2, 1));
  robots.ingest(mission(5, 0, 0));  // the sender's sample, arriving late
  EXPECT_EQ(robots.find("r1")->mission.current, 2u);
  robots.ingest(mission(5, 0, 2));  // wrapped: another lap
  EXPECT_EQ(robots.find("r1")->mission.laps, 2u);
  robots.ingest(mission(5, 1, 2, MissionStatus::Cancelled));
  robots.ingest(mission(5, 2, 2));
  EXPECT_EQ(robots.find("r1")->mission.status, MissionStatus::Cancelled);
  robots.ingest(mission(6, 0, 0));  // a new mission replaces it
  EXPECT_EQ(robots.find("r1")->mission.mission_id, 6u);
  EXPECT_EQ(robots.find("r1")->mission.status, MissionStatus::Active);
}

}  // namespace
}  // namespace slam::viewer
