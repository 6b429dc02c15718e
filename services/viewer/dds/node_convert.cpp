// IDL <-> plain viewer types (see node_convert.hpp).
#include "viewer/dds/node_convert.hpp"

#include "common/core/geometry.hpp"

namespace slam::viewer {
ObservationData from_idl(const slam::RobotObservation& o) {
  ObservationData d;
  d.robot_id = o.robot_id().to_string();
  d.seq = o.seq();
  d.pose = msg::from_idl(o.pose());
  d.hits_xy.reserve(o.hits().size() * 2);
  for (const auto& h : o.hits()) {
    d.hits_xy.push_back(static_cast<float>(h.x()));
    d.hits_xy.push_back(static_cast<float>(h.y()));
  }
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
  for (const auto& s : w.walls()) d.walls.emplace_back(msg::from_idl(s.a()), msg::from_idl(s.b()));
  return d;
}

SimTruthData from_idl(const slam::SimGroundTruth& t) {
  SimTruthData d;
  d.paused = t.paused();
  for (const auto& r : t.robots())
    d.robots.push_back(
        {r.robot_id().to_string(), msg::from_idl(r.true_pose()), msg::from_idl(r.reported_pose())});
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

ForgetData from_idl(const slam::ForgetRobot& f) {
  return {f.robot_id().to_string()};
}

slam::NavGoal to_idl(const GoalCommand& c, uint64_t goal_id) {
  slam::NavGoal g;
  g.robot_id(c.robot_id);
  g.goal_id(goal_id);
  g.mode(msg::to_idl(c.mode));
  g.target(msg::to_idl(c.target));
  g.square_size(c.square_size);
  g.square_anchor(c.square_centred ? slam::SQUARE_CENTRED : slam::SQUARE_CORNER);
  return g;
}

slam::NavMission to_idl(const MissionCommand& c, uint64_t mission_id) {
  slam::NavMission m;
  m.robot_id(c.robot_id);
  m.mission_id(mission_id);
  for (const Vec2& w : c.waypoints) m.waypoints().push_back(msg::to_idl(w));
  m.loop(c.loop);
  m.status(slam::MISSION_ACTIVE);
  return m;
}

slam::MapEdit to_idl(const MapEditCommand& c, uint64_t request_id) {
  slam::MapEdit e;
  e.request_id(request_id);
  e.kind(static_cast<slam::MapEditKind>(c.kind));
  e.point(msg::to_idl(c.point));
  e.robot_id(c.robot_id);
  return e;
}

slam::GridConfig to_idl(const GridConfigCommand& c, uint64_t request_id) {
  slam::GridConfig g;
  g.request_id(request_id);
  g.resolution(c.resolution);
  g.origin(msg::to_idl(c.origin));
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

slam::PlacementAnswer to_idl(const PlacementAnswerCommand& c, uint64_t request_id) {
  slam::PlacementAnswer a;
  a.request_id(request_id);
  a.robot_id(c.robot_id);
  a.verdict(c.accept ? slam::PLACEMENT_ACCEPT : slam::PLACEMENT_REJECT);
  return a;
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
  r.start(msg::to_idl(c.start));
  r.goal(msg::to_idl(c.goal));
  r.algorithm(c.algorithm);
  r.time_budget_s(1.0);
  return r;
}

}  // namespace slam::viewer
