// IDL <-> plain viewer types (see node_convert.hpp).
#include "viewer/dds/node_convert.hpp"

#include "common/core/geometry.hpp"

namespace slam::viewer {
namespace {

Pose pose(const slam::Pose2& p) {
  return {p.x(), p.y(), p.theta()};
}
Vec2 vec(const slam::Point2& p) {
  return {p.x(), p.y()};
}
slam::Point2 point(Vec2 v) {
  slam::Point2 p;
  p.x(v.x);
  p.y(v.y);
  return p;
}

}  // namespace

GridSnapshotData from_idl(const slam::GridSnapshot& s) {
  GridSnapshotData d;
  d.layout_id = s.layout_id();
  d.version = s.version();
  d.info = {s.info().width(), s.info().height(), s.info().resolution(), vec(s.info().origin()),
            s.info().inflation_radius()};
  d.cells = s.cells();
  return d;
}

GridPatchData from_idl(const slam::GridTiles& p) {
  return {p.layout_id(), p.version(), p.tile_side(), p.encoding(), p.tiles(), p.data()};
}

ObservationData from_idl(const slam::RobotObservation& o) {
  ObservationData d;
  d.robot_id = o.robot_id().to_string();
  d.seq = o.seq();
  d.pose = pose(o.pose());
  d.hits_xy.reserve(o.hits().size() * 2);
  for (const auto& h : o.hits()) {
    d.hits_xy.push_back(static_cast<float>(h.x()));
    d.hits_xy.push_back(static_cast<float>(h.y()));
  }
  return d;
}

RobotStateData from_idl(const slam::RobotState& s) {
  RobotStateData d;
  d.robot_id = s.robot_id().to_string();
  d.protocol_v2 = s.protocol() == slam::PROTOCOL_V2;
  d.online = s.presence() == slam::PRESENCE_ONLINE;
  d.pose = pose(s.pose());
  d.has_heading = s.has_heading();
  d.first_seen_ns = s.first_seen_ns();
  d.last_seen_ns = s.last_seen_ns();
  d.messages = s.messages();
  d.points = s.points();
  d.rejected = s.rejected();
  d.battery = s.battery();
  d.status = s.status().to_string();
  return d;
}

RobotPoseData from_idl(const slam::DigestRobot& r) {
  RobotPoseData d;
  d.robot_id = r.robot_id().to_string();
  d.pose = pose(r.pose());
  d.has_heading = r.has_heading();
  d.online = r.presence() == slam::PRESENCE_ONLINE;
  d.last_seen_ns = r.last_seen_ns();
  return d;
}

RobotPathData from_idl(const slam::RobotPath& p) {
  RobotPathData d;
  d.robot_id = p.robot_id().to_string();
  d.goal_id = p.goal_id();
  d.mode = static_cast<GoalMode>(p.mode());
  d.status = static_cast<GoalStatus>(p.status());
  d.target = vec(p.target());
  d.waypoints.reserve(p.waypoints().size());
  for (const auto& w : p.waypoints()) d.waypoints.push_back(vec(w));
  d.current = p.current();
  d.reason = p.reason().to_string();
  return d;
}

MissionData from_idl(const slam::NavMission& m) {
  MissionData d;
  d.robot_id = m.robot_id().to_string();
  d.mission_id = m.mission_id();
  d.waypoints.reserve(m.waypoints().size());
  for (const auto& w : m.waypoints()) d.waypoints.push_back(vec(w));
  d.loop = m.loop();
  d.current = m.current();
  d.laps = m.laps();
  d.status = static_cast<MissionStatus>(m.status());
  d.reason = m.reason().to_string();
  return d;
}

HeartbeatData from_idl(const slam::Heartbeat& h) {
  HeartbeatData d;
  d.service = h.service().to_string();
  d.instance_id = h.instance_id().to_string();
  d.pid = h.pid();
  d.host = h.host().to_string();
  d.uptime_s = h.uptime_s();
  d.state = static_cast<ServiceState>(h.state());
  for (const auto& c : h.counters()) d.counters.emplace_back(c.name().to_string(), c.value());
  return d;
}

MqttEntry from_idl(const slam::MqttTraffic& t) {
  return {t.seq(),     t.stamp_ns(),    t.direction() == slam::MQTT_INBOUND, t.topic().to_string(),
          t.payload(), t.payload_size()};
}

MqttSubscriptionsData from_idl(const slam::MqttSubscriptions& s) {
  MqttSubscriptionsData d;
  d.connected = s.connected();
  d.broker = s.broker().to_string();
  for (const auto& f : s.filters()) d.filters.push_back(f.to_string());
  return d;
}

SimWorldData from_idl(const slam::SimWorld& w) {
  SimWorldData d;
  d.name = w.name().to_string();
  d.width_m = w.width_m();
  d.height_m = w.height_m();
  for (const auto& s : w.walls()) d.walls.emplace_back(vec(s.a()), vec(s.b()));
  return d;
}

SimTruthData from_idl(const slam::SimGroundTruth& t) {
  SimTruthData d;
  d.paused = t.paused();
  for (const auto& r : t.robots())
    d.robots.push_back({r.robot_id().to_string(), pose(r.true_pose()), pose(r.reported_pose())});
  return d;
}

MapReplyData from_idl(const slam::MapReply& r) {
  return {r.request_id(), static_cast<int>(r.result()), r.message().to_string()};
}

MqttReplyData from_idl(const slam::MqttReply& r) {
  return {{r.request_id(), r.ok(), r.message().to_string()}};
}

SimReplyData from_idl(const slam::SimReply& r) {
  return {{r.command_id(), r.ok(), r.message().to_string()}};
}

AlertData from_idl(const slam::Alert& a) {
  return {a.alert_id().to_string(),
          static_cast<AlertKind>(a.kind()),
          a.subject().to_string(),
          a.active(),
          a.raised_ns(),
          a.message().to_string(),
          a.raised_by().to_string()};
}

ForgetData from_idl(const slam::ForgetRobot& f) {
  return {f.robot_id().to_string()};
}

PathReplyData from_idl(const slam::PathReply& r) {
  PathReplyData d;
  d.request_id = r.request_id();
  d.ok = r.status() == slam::PLAN_OK;
  d.reason = r.reason().to_string();
  for (const auto& p : r.path()) d.path.push_back(vec(p));
  d.length_m = r.length_m();
  d.planning_time_s = r.planning_time_s();
  return d;
}

PoseCorrectionData from_idl(const slam::PoseCorrection& c) {
  return {c.robot_id().to_string(),
          c.version(),
          pose(c.map_from_odom()),
          c.keyframes(),
          c.loop_closures(),
          static_cast<CorrectionSource>(c.source()),
          position_sigma(c.covariance())};
}

slam::NavGoal to_idl(const GoalCommand& c, uint64_t goal_id) {
  slam::NavGoal g;
  g.robot_id(c.robot_id);
  g.goal_id(goal_id);
  g.mode(static_cast<slam::GoalMode>(c.mode));
  g.target(point(c.target));
  g.square_size(c.square_size);
  g.square_anchor(c.square_centred ? slam::SQUARE_CENTRED : slam::SQUARE_CORNER);
  return g;
}

slam::NavMission to_idl(const MissionCommand& c, uint64_t mission_id) {
  slam::NavMission m;
  m.robot_id(c.robot_id);
  m.mission_id(mission_id);
  for (const Vec2& w : c.waypoints) m.waypoints().push_back(point(w));
  m.loop(c.loop);
  m.status(slam::MISSION_ACTIVE);
  return m;
}

slam::MapEdit to_idl(const MapEditCommand& c, uint64_t request_id) {
  slam::MapEdit e;
  e.request_id(request_id);
  e.kind(static_cast<slam::MapEditKind>(c.kind));
  e.point(point(c.point));
  e.robot_id(c.robot_id);
  return e;
}

slam::GridConfig to_idl(const GridConfigCommand& c, uint64_t request_id) {
  slam::GridConfig g;
  g.request_id(request_id);
  g.resolution(c.resolution);
  g.origin(point(c.origin));
  g.width_m(c.width_m);
  g.height_m(c.height_m);
  g.inflation_radius(c.inflation_radius);
  g.legacy_mode(c.legacy_mode);
  return g;
}

slam::MqttRequest to_idl(const MqttRequestCommand& c, uint64_t request_id) {
  slam::MqttRequest r;
  r.request_id(request_id);
  r.kind(static_cast<slam::MqttRequestKind>(c.kind));
  r.topic(c.topic);
  r.payload(c.payload);
  r.qos(c.qos);
  r.retain(c.retain);
  return r;
}

slam::SimControl to_idl(const SimCommand& c, uint64_t command_id) {
  slam::SimControl s;
  s.command_id(command_id);
  s.kind(static_cast<slam::SimCommandKind>(c.kind));
  s.count(c.count);
  s.robot_id(c.robot_id);
  s.world(c.world);
  s.range_noise_sd(c.range_noise_sd);
  s.dropout(c.dropout);
  s.odometry_drift(c.odometry_drift);
  s.speed_factor(c.speed_factor);
  return s;
}

slam::MapFileRequest to_idl(const MapFileCommand& c, uint64_t request_id) {
  slam::MapFileRequest r;
  r.request_id(request_id);
  r.action(c.import ? slam::MAP_IMPORT : slam::MAP_EXPORT);
  r.yaml_path(c.yaml_path);
  return r;
}

slam::InitialPose to_idl(const InitialPoseCommand& c, uint64_t request_id) {
  slam::InitialPose p;
  p.request_id(request_id);
  p.robot_id(c.robot_id);
  slam::Pose2 pose;
  pose.x(c.pose.x);
  pose.y(c.pose.y);
  pose.theta(c.pose.theta);
  p.pose(pose);
  return p;
}

slam::ForgetRobot to_idl(const ForgetCommand& c, uint64_t request_id) {
  slam::ForgetRobot f;
  f.request_id(request_id);
  f.robot_id(c.robot_id);
  return f;
}

slam::PathRequest to_idl(const PathPreviewCommand& c, uint64_t request_id) {
  slam::PathRequest r;
  r.request_id(request_id);
  r.client_id("viewer");
  r.start(point(c.start));
  r.goal(point(c.goal));
  r.algorithm(c.algorithm);
  r.time_budget_s(1.0);
  return r;
}

}  // namespace slam::viewer
