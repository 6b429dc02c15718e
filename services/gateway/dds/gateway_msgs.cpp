// Core structs <-> generated DDS types.
#include "gateway/dds/gateway_msgs.hpp"

namespace slam::gateway {

namespace {

void copy_points(const std::vector<protocol::Point>& in, std::vector<slam::Point2>& out) {
  out.resize(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    out[i].x(in[i].x);
    out[i].y(in[i].y);
  }
}

slam::RobotProtocol to_dds(Protocol p) {
  return p == Protocol::V1 ? slam::PROTOCOL_V1 : slam::PROTOCOL_V2;
}

}  // namespace

slam::RobotObservation& append_observation(slam::RobotObservationBatch& batch,
                                           std::vector<slam::RobotObservation>& spare) {
  if (spare.empty()) return batch.observations().emplace_back();
  batch.observations().push_back(std::move(spare.back()));
  spare.pop_back();
  return batch.observations().back();
}

void recycle_observations(slam::RobotObservationBatch& batch, std::vector<slam::RobotObservation>& spare) {
  for (slam::RobotObservation& o : batch.observations()) spare.push_back(std::move(o));
  batch.observations().clear();
}

void fill_observation(std::string_view robot_id, std::uint64_t seq, std::int64_t stamp_ns, Protocol protocol,
                      const protocol::DecodedObservation& in, slam::RobotObservation& out) {
  set_text(out.robot_id(), robot_id);
  out.seq(seq);
  out.stamp_ns(stamp_ns);
  out.robot_stamp_ns(in.robot_stamp_ns);
  out.protocol(to_dds(protocol));
  out.pose().x(in.x);
  out.pose().y(in.y);
  out.pose().theta(in.has_heading ? in.theta : 0.0);
  out.has_heading(in.has_heading);
  copy_points(in.hits, out.hits());
  copy_points(in.misses, out.misses());
}

void fill_state(const RobotRecord& in, const Pose& map_pose, slam::RobotState& out) {
  set_text(out.robot_id(), in.id);
  out.protocol(to_dds(in.protocol));
  out.presence(in.presence == Presence::Online ? slam::PRESENCE_ONLINE : slam::PRESENCE_OFFLINE);
  out.pose().x(map_pose.x);
  out.pose().y(map_pose.y);
  out.pose().theta(map_pose.theta);
  out.has_heading(in.has_heading);
  out.first_seen_ns(in.first_seen_ns);
  out.last_seen_ns(in.last_seen_ns);
  out.messages(in.messages);
  out.points(in.points);
  out.rejected(in.rejected);
  out.battery(in.battery);
  set_text(out.status(), in.status);
}

void fill_odometry(const RobotRecord& in, std::uint64_t correction_version, slam::RobotOdometry& out) {
  set_text(out.robot_id(), in.id);
  out.stamp_ns(in.last_seen_ns);
  out.odom_pose().x(in.x);
  out.odom_pose().y(in.y);
  out.odom_pose().theta(in.theta);
  out.has_heading(in.has_heading);
  out.correction_version(correction_version);
}

Correction to_correction(const slam::PoseCorrection& in) {
  const slam::Pose2& t = in.map_from_odom();
  return {{t.x(), t.y(), t.theta()}, in.version()};
}

CorrectionInput to_input(const slam::PoseCorrection& in) {
  return {in.robot_id().to_string(), to_correction(in)};
}

WaypointInput to_input(const slam::WaypointCommand& in) {
  WaypointInput out{in.robot_id().to_string(), in.seq(), {in.waypoint().x(), in.waypoint().y()}, {}};
  to_points(in.remaining(), out.remaining);
  return out;
}

MqttRequestInput to_input(const slam::MqttRequest& in) {
  RequestKind kind = static_cast<RequestKind>(static_cast<std::uint32_t>(in.kind()));
  switch (in.kind()) {
    case slam::MQTT_PUBLISH:
      kind = RequestKind::Publish;
      break;
    case slam::MQTT_SUBSCRIBE:
      kind = RequestKind::Subscribe;
      break;
    case slam::MQTT_UNSUBSCRIBE:
      kind = RequestKind::Unsubscribe;
      break;
  }
  return {in.request_id(), kind, in.topic().to_string(), in.payload(), in.qos(), in.retain()};
}

ProtocolReport to_input(const slam::RobotState& in) {
  return {in.robot_id().to_string(),
          {in.protocol() == slam::PROTOCOL_V1 ? Protocol::V1 : Protocol::V2, in.last_seen_ns()}};
}

void fill_traffic(const TrafficRecord& in, slam::MqttTraffic& out) {
  out.seq(in.seq);
  out.stamp_ns(in.stamp_ns);
  out.direction(in.direction == TrafficDirection::Inbound ? slam::MQTT_INBOUND : slam::MQTT_OUTBOUND);
  set_text(out.topic(), in.topic);
  out.payload().assign(in.payload.begin(), in.payload.end());
  out.payload_size(in.payload_size);
}

void fill_digest(std::string_view gateway_id, std::int64_t stamp_ns, std::span<const DigestRobotEntry> robots,
                 slam::FleetDigest& out) {
  set_text(out.gateway_id(), gateway_id);
  out.stamp_ns(stamp_ns);
  out.robots().resize(robots.size());
  for (std::size_t i = 0; i < robots.size(); ++i) {
    const DigestRobotEntry& in = robots[i];
    slam::DigestRobot& r = out.robots()[i];
    set_text(r.robot_id(), in.id);
    r.pose().x(in.pose.x);
    r.pose().y(in.pose.y);
    r.pose().theta(in.has_heading ? in.pose.theta : 0.0);
    r.has_heading(in.has_heading);
    r.presence(in.online ? slam::PRESENCE_ONLINE : slam::PRESENCE_OFFLINE);
    r.last_seen_ns(in.last_seen_ns);
  }
}

void fill_points(std::string_view gateway_id, std::int64_t stamp_ns,
                 std::span<const DigestPointsEntry> robots, slam::FleetPoints& out) {
  set_text(out.gateway_id(), gateway_id);
  out.stamp_ns(stamp_ns);
  out.robots().resize(robots.size());
  for (std::size_t i = 0; i < robots.size(); ++i) {
    const DigestPointsEntry& in = robots[i];
    slam::DigestRobotPoints& r = out.robots()[i];
    set_text(r.robot_id(), in.id);
    r.stamp_ns(in.stamp_ns);
    r.points().resize(in.points.size());
    for (std::size_t k = 0; k < in.points.size(); ++k) {
      r.points()[k].x(static_cast<float>(in.points[k].x));
      r.points()[k].y(static_cast<float>(in.points[k].y));
    }
  }
}

void to_points(const std::vector<slam::Point2>& in, std::vector<protocol::Point>& out) {
  out.resize(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) out[i] = {in[i].x(), in[i].y()};
}

}  // namespace slam::gateway
