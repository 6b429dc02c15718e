// The fleet's plain messages: their names, and the conversion from the Fast DDS samples.
#include "common/fastdds/fleet_messages.hpp"

#include <gtest/gtest.h>

namespace slam::msg {
namespace {

TEST(FleetMessageNames, EveryValueHasItsName) {
  EXPECT_STREQ(goal_mode_name(GoalMode::Idle), "idle");
  EXPECT_STREQ(goal_mode_name(GoalMode::Explore), "explore");
  EXPECT_STREQ(goal_mode_name(GoalMode::Stop), "stop");
  EXPECT_STREQ(goal_status_name(GoalStatus::Reached), "reached");
  EXPECT_STREQ(mission_status_name(MissionStatus::Cancelled), "cancelled");
  EXPECT_STREQ(plan_status_name(PlanStatus::StartBlocked), "START_BLOCKED");
  EXPECT_STREQ(plan_status_id(PlanStatus::StartBlocked), "start_blocked");
  EXPECT_STREQ(correction_source_id(CorrectionSource::Loop), "loop");
  EXPECT_STREQ(correction_source_name(CorrectionSource::Loop), "loop closure");
  EXPECT_STREQ(service_state_name(ServiceState::Stopping), "stopping");
}

TEST(FleetMessageNames, AValueOfANewerPeerIsAQuestionMark) {
  EXPECT_STREQ(goal_mode_name(static_cast<GoalMode>(7)), "?");
  EXPECT_STREQ(service_state_name(static_cast<ServiceState>(3)), "?");
}

TEST(FleetMessageNames, GoalModesParseFromTheirNames) {
  for (size_t i = 0; i < kGoalModeNames.size(); ++i)
    EXPECT_EQ(parse_goal_mode(kGoalModeNames[i]), static_cast<GoalMode>(i)) << kGoalModeNames[i];
  EXPECT_EQ(parse_goal_mode("PLANNED"), std::nullopt);
  EXPECT_EQ(parse_goal_mode("fly"), std::nullopt);
  EXPECT_EQ(parse_goal_mode(""), std::nullopt);
}

TEST(FleetMessagesFromIdl, EnumerationsKeepTheirValues) {
  EXPECT_EQ(from_idl(slam::GOAL_EXPLORE), GoalMode::Explore);
  EXPECT_EQ(to_idl(GoalMode::Home), slam::GOAL_HOME);
  EXPECT_EQ(from_idl(slam::GOAL_STATUS_FAILED), GoalStatus::Failed);
  EXPECT_EQ(to_idl(GoalStatus::Reached), slam::GOAL_STATUS_REACHED);
  EXPECT_EQ(from_idl(slam::MISSION_DONE), MissionStatus::Done);
  EXPECT_EQ(to_idl(MissionStatus::Failed), slam::MISSION_FAILED);
  EXPECT_EQ(from_idl(slam::PLAN_NO_MAP), PlanStatus::NoMap);
  EXPECT_EQ(to_idl(PlanStatus::Timeout), slam::PLAN_TIMEOUT);
  EXPECT_EQ(from_idl(slam::CORRECTION_OPERATOR), CorrectionSource::Operator);
  EXPECT_EQ(from_idl(slam::SERVICE_RUNNING), ServiceState::Running);
  EXPECT_EQ(from_idl(slam::ALERT_SERVICE_SILENT), AlertKind::ServiceSilent);
  EXPECT_EQ(to_idl(AlertKind::BatteryLow), slam::ALERT_BATTERY_LOW);
  EXPECT_EQ(to_idl(AlertKind::RobotLost), slam::ALERT_ROBOT_LOST);
  EXPECT_EQ(from_idl(slam::SQUARE_CENTRED), SquareAnchor::Centred);
}

slam::Point2 point(double x, double y) {
  return to_idl(Vec2{x, y});
}

TEST(FleetMessagesFromIdl, RobotPathKeepsEveryField) {
  slam::RobotPath s;
  s.robot_id("sim-1");
  s.goal_id(7);
  s.mode(slam::GOAL_PLANNED);
  s.status(slam::GOAL_STATUS_ACTIVE);
  s.target(point(3, 4));
  s.waypoints({point(1, 0), point(3, 4)});
  s.current(1);
  s.reason("why");
  const RobotPath p = from_idl(s);
  EXPECT_EQ(p.robot_id, "sim-1");
  EXPECT_EQ(p.goal_id, 7u);
  EXPECT_EQ(p.mode, GoalMode::Planned);
  EXPECT_EQ(p.status, GoalStatus::Active);
  EXPECT_EQ(p.target, (Vec2{3, 4}));
  EXPECT_EQ(p.waypoints, (std::vector<Vec2>{{1, 0}, {3, 4}}));
  EXPECT_EQ(p.current, 1u);
  EXPECT_EQ(p.reason, "why");
}

TEST(FleetMessagesFromIdl, HeartbeatKeepsItsCountersInOrder) {
  slam::Heartbeat s;
  s.service("mapper");
  s.instance_id("vm:1");
  s.pid(1);
  s.host("vm");
  s.stamp_ns(5);
  s.uptime_s(2.5);
  s.state(slam::SERVICE_STOPPING);
  slam::Counter a, b;
  a.name("points");
  a.value(9);
  b.name("errors");
  b.value(-1);
  s.counters({a, b});
  const Heartbeat h = from_idl(s);
  EXPECT_EQ(h.service, "mapper");
  EXPECT_EQ(h.instance_id, "vm:1");
  EXPECT_EQ(h.pid, 1u);
  EXPECT_EQ(h.host, "vm");
  EXPECT_EQ(h.stamp_ns, 5);
  EXPECT_EQ(h.uptime_s, 2.5);
  EXPECT_EQ(h.state, ServiceState::Stopping);
  using Counter = std::pair<std::string, int64_t>;
  EXPECT_EQ(h.counters, (std::vector<Counter>{{"points", 9}, {"errors", -1}}));
}

TEST(FleetMessagesFromIdl, AlertKeepsEveryField) {
  slam::Alert s;
  s.alert_id("battery/r1");
  s.kind(slam::ALERT_BATTERY_LOW);
  s.subject("r1");
  s.active(true);
  s.raised_ns(10);
  s.stamp_ns(20);
  s.message("r1 at 9 %");
  s.raised_by("vm:2");
  const Alert a = from_idl(s);
  EXPECT_EQ(a.alert_id, "battery/r1");
  EXPECT_EQ(a.kind, AlertKind::BatteryLow);
  EXPECT_EQ(a.subject, "r1");
  EXPECT_TRUE(a.active);
  EXPECT_EQ(a.raised_ns, 10);
  EXPECT_EQ(a.stamp_ns, 20);
  EXPECT_EQ(a.message, "r1 at 9 %");
  EXPECT_EQ(a.raised_by, "vm:2");
}

TEST(FleetMessagesFromIdl, RobotStateAndDigestRobot) {
  slam::RobotState s;
  s.robot_id("r1");
  s.protocol(slam::PROTOCOL_V2);
  s.presence(slam::PRESENCE_OFFLINE);
  slam::Pose2 pose;
  pose.x(1);
  pose.y(2);
  pose.theta(0.5);
  s.pose(pose);
  s.has_heading(true);
  s.first_seen_ns(1);
  s.last_seen_ns(2);
  s.messages(3);
  s.points(4);
  s.rejected(5);
  s.battery(0.5f);
  s.status("charging");
  const RobotState r = from_idl(s);
  EXPECT_EQ(r.robot_id, "r1");
  EXPECT_TRUE(r.protocol_v2);
  EXPECT_FALSE(r.online);
  EXPECT_EQ(r.pose.x, 1.0);
  EXPECT_EQ(r.pose.y, 2.0);
  EXPECT_EQ(r.pose.theta, 0.5);
  EXPECT_TRUE(r.has_heading);
  EXPECT_EQ(r.first_seen_ns, 1);
  EXPECT_EQ(r.last_seen_ns, 2);
  EXPECT_EQ(r.messages, 3u);
  EXPECT_EQ(r.points, 4u);
  EXPECT_EQ(r.rejected, 5u);
  EXPECT_EQ(r.battery, 0.5f);
  EXPECT_EQ(r.status, "charging");

  slam::DigestRobot d;
  d.robot_id("r2");
  d.pose(pose);
  d.presence(slam::PRESENCE_ONLINE);
  d.last_seen_ns(9);
  const RobotPose p = from_idl(d);
  EXPECT_EQ(p.robot_id, "r2");
  EXPECT_EQ(p.pose.theta, 0.5);
  EXPECT_FALSE(p.has_heading);
  EXPECT_TRUE(p.online);
  EXPECT_EQ(p.last_seen_ns, 9);
}

TEST(FleetMessagesFromIdl, PoseCorrectionMissionAndPathReply) {
  slam::PoseCorrection c;
  c.robot_id("r1");
  c.version(3);
  c.covariance({0.04, 0, 0, 0.01, 0, 0.001});
  c.keyframes(12);
  c.loop_closures(2);
  c.source(slam::CORRECTION_LOOP);
  const PoseCorrection pc = from_idl(c);
  EXPECT_EQ(pc.version, 3u);
  EXPECT_DOUBLE_EQ(position_sigma(pc.covariance), 0.2);
  EXPECT_EQ(pc.keyframes, 12u);
  EXPECT_EQ(pc.loop_closures, 2u);
  EXPECT_EQ(pc.source, CorrectionSource::Loop);

  slam::NavMission m;
  m.robot_id("r1");
  m.mission_id(4);
  m.waypoints({point(1, 1), point(2, 2)});
  m.loop(true);
  m.current(1);
  m.laps(6);
  m.status(slam::MISSION_FAILED);
  m.reason("blocked");
  const Mission mission = from_idl(m);
  EXPECT_EQ(mission.mission_id, 4u);
  EXPECT_EQ(mission.waypoints.size(), 2u);
  EXPECT_TRUE(mission.loop);
  EXPECT_EQ(mission.current, 1u);
  EXPECT_EQ(mission.laps, 6u);
  EXPECT_EQ(mission.status, MissionStatus::Failed);
  EXPECT_EQ(mission.reason, "blocked");

  slam::PathReply r;
  r.request_id(8);
  r.status(slam::PLAN_NO_PATH);
  r.reason("walled in");
  r.path({point(0, 0)});
  r.length_m(1.5);
  r.planning_time_s(0.25);
  const PathReply reply = from_idl(r);
  EXPECT_EQ(reply.request_id, 8u);
  EXPECT_EQ(reply.status, PlanStatus::NoPath);
  EXPECT_EQ(reply.reason, "walled in");
  EXPECT_EQ(reply.path, (std::vector<Vec2>{{0, 0}}));
  EXPECT_EQ(reply.length_m, 1.5);
  EXPECT_EQ(reply.planning_time_s, 0.25);
}

TEST(FleetMessagesFromIdl, GridSnapshotAndTiles) {
  slam::GridSnapshot s;
  s.layout_id(2);
  s.version(5);
  s.stamp_ns(6);
  slam::GridInfo info;
  info.width(2);
  info.height(1);
  info.resolution(0.05);
  info.origin(point(-1, -2));
  info.inflation_radius(0.2);
  s.info(info);
  s.cells({1, 2});
  const GridSnapshot g = from_idl(s);
  EXPECT_EQ(g.layout_id, 2u);
  EXPECT_EQ(g.version, 5u);
  EXPECT_EQ(g.stamp_ns, 6);
  EXPECT_EQ(g.info.width, 2u);
  EXPECT_EQ(g.info.height, 1u);
  EXPECT_EQ(g.info.resolution, 0.05);
  EXPECT_EQ(g.info.origin, (Vec2{-1, -2}));
  EXPECT_EQ(g.info.inflation_radius, 0.2);
  EXPECT_EQ(g.cells, (std::vector<uint8_t>{1, 2}));

  slam::GridTiles t;
  t.layout_id(2);
  t.version(6);
  t.stamp_ns(7);
  t.tile_side(32);
  t.encoding(1);
  t.tiles({0, 3});
  t.data({9});
  const GridTiles tiles = from_idl(t);
  EXPECT_EQ(tiles.layout_id, 2u);
  EXPECT_EQ(tiles.version, 6u);
  EXPECT_EQ(tiles.stamp_ns, 7);
  EXPECT_EQ(tiles.tile_side, 32);
  EXPECT_EQ(tiles.encoding, 1);
  EXPECT_EQ(tiles.tiles, (std::vector<uint32_t>{0, 3}));
  EXPECT_EQ(tiles.data, (std::vector<uint8_t>{9}));
}

}  // namespace
}  // namespace slam::msg
