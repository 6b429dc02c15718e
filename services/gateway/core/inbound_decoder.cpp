// InboundDecoder: parse_topic + decode_message on the MQTT thread; apply_inbound: the registry decides
// what the message means, on the loop.
#include "gateway/core/inbound_decoder.hpp"

#include <fmt/format.h>

#include <utility>

#include "protocol/text_check.hpp"

namespace slam::gateway {

namespace {

const char* connection_text(protocol::VdaConnection c) {
  switch (c) {
    case protocol::VdaConnection::Online:
      return "ONLINE";
    case protocol::VdaConnection::Offline:
      return "OFFLINE";
    case protocol::VdaConnection::ConnectionBroken:
      return "CONNECTIONBROKEN";
  }
  return "?";
}

// The registry's view of a VDA message: the pose when the robot knows where it is, the status text.
void fill_vda(InboundMessage& out) {
  const protocol::VdaMessage& vda = out.vda;
  protocol::DecodedObservation& observation = out.message.observation;
  observation.clear();
  if (vda.has_position && vda.position_initialized) {
    observation.x = vda.x;
    observation.y = vda.y;
    observation.theta = vda.theta;
    observation.has_pose = observation.has_heading = true;
  }
  protocol::DecodedStatus& status = out.message.status;
  status.clear();
  status.battery = vda.battery;
  if (vda.topic == protocol::VdaTopic::Connection) {
    status.state = connection_text(vda.connection);
    status.offline = vda.connection != protocol::VdaConnection::Online;
  } else {
    status.state = vda.operating_mode;
  }
}

}  // namespace

InboundDecoder::InboundDecoder(const protocol::CodecLimits& limits, VdaInbound vda)
    : limits_(limits), vda_(std::move(vda)), vda_prefix_(vda_.tree.interface_name + "/") {
  vda_robots_.insert(vda_.robots.begin(), vda_.robots.end());
}

bool InboundDecoder::decode_vda(std::string_view topic, std::span<const std::uint8_t> payload,
                                InboundMessage& out) const {
  out.is_vda = true;
  protocol::VdaAddress address;
  out.status = protocol::parse_vda_topic(topic, vda_.tree, address);
  if (!out.status) return false;
  out.vda_manufacturer.assign(address.manufacturer);
  out.vda_serial_number.assign(address.serial_number);
  out.vda.topic = address.topic;
  out.status = protocol::vda_robot_id(address.manufacturer, address.serial_number, out.robot_id);
  if (!out.status) return false;
  if (!vda_robots_.empty()) {
    const std::string key = fmt::format("{}/{}", out.vda_manufacturer, out.vda_serial_number);
    if (!vda_robots_.contains(key)) {
      out.status = {protocol::RejectReason::UnknownRobot,
                    fmt::format("'{}' is not one of the configured VDA robots (vda-robot)",
                                protocol::escape_for_log(key))};
      out.robot_id.clear();  // not ours: counted against no robot
      return false;
    }
  }
  out.status = protocol::decode_vda_message(address.topic, address, payload, vda_.tree, limits_, out.vda);
  if (!out.status) return false;
  fill_vda(out);
  return true;
}

std::size_t InboundMessage::points() const {
  if (!status || message.kind == protocol::TopicKind::V2Status) return 0;
  return message.observation.hits.size() + message.observation.misses.size();
}

bool InboundDecoder::decode(std::string_view topic, std::span<const std::uint8_t> payload, Instant received,
                            InboundMessage& out) const {
  out.topic.assign(topic);
  out.robot_id.clear();
  out.received = received;
  out.is_vda = false;
  if (vda_.enabled && topic.starts_with(vda_prefix_)) {
    if (decode_vda(topic, payload, out)) return true;
    out.message.observation.clear();
    out.message.status.clear();
    return false;
  }
  protocol::ParsedTopic parsed;
  out.status = protocol::parse_topic(topic, parsed);
  if (!out.status) {
    out.message.observation.clear();
    out.message.status.clear();
    return false;
  }
  out.robot_id.assign(parsed.robot_id);
  out.status = protocol::decode_message(parsed.kind, payload, limits_, out.message);
  return out.status.is_ok();
}

InboundResult apply_inbound(RobotRegistry& registry, InboundMessage& message) {
  InboundResult result;
  if (!message.status) {
    if (!message.robot_id.empty()) registry.count_rejected(message.robot_id);
    return result;
  }
  bool is_status = message.message.kind == protocol::TopicKind::V2Status;
  if (message.is_vda) {
    const protocol::VdaTopic topic = message.vda.topic;
    is_status = !message.message.observation.has_pose;
    // Nothing for the registry: no pose, no status (the robot's address is the loop's business). A
    // connection only changes a known robot's presence: a robot first heard through it would have no
    // pose, and its record at (0, 0) would be where the planner takes its home to be.
    if (topic == protocol::VdaTopic::Factsheet || (topic == protocol::VdaTopic::Visualization && is_status) ||
        (topic == protocol::VdaTopic::Connection && registry.find(message.robot_id) == nullptr)) {
      result.kind = InboundKind::Status;
      return result;
    }
  }
  result.accepted = is_status ? registry.accept_status(message.robot_id, message.message.status,
                                                       message.received, message.protocol())
                              : registry.accept_observation(message.robot_id, message.protocol(),
                                                            message.message.observation, message.received);
  if (message.is_vda && !is_status && message.vda.topic == protocol::VdaTopic::State &&
      result.accepted.kind == AcceptResult::Kind::Accepted)
    registry.set_status(message.robot_id, message.message.status);
  switch (result.accepted.kind) {
    case AcceptResult::Kind::Accepted:
      result.kind = is_status ? InboundKind::Status : InboundKind::Observation;
      return result;
    case AcceptResult::Kind::NoPose:
      message.status = {protocol::RejectReason::MissingField,
                        "points message without pose, and no earlier pose from this robot to cast rays from"};
      registry.count_rejected(message.robot_id);
      result.kind = InboundKind::Rejected;
      return result;
    case AcceptResult::Kind::RegistryFull:
      break;
  }
  result.kind = InboundKind::Refused;
  return result;
}

}  // namespace slam::gateway
