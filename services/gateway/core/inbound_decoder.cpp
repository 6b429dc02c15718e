// InboundDecoder: parse_topic + decode_message on the MQTT thread; apply_inbound: the registry decides
// what the message means, on the loop.
#include "gateway/core/inbound_decoder.hpp"

namespace slam::gateway {

std::size_t InboundMessage::points() const {
  if (!status || message.kind == protocol::TopicKind::V2Status) return 0;
  return message.observation.hits.size() + message.observation.misses.size();
}

bool InboundDecoder::decode(std::string_view topic, std::span<const std::uint8_t> payload, Instant received,
                            InboundMessage& out) const {
  out.topic.assign(topic);
  out.robot_id.clear();
  out.received = received;
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
  const bool is_status = message.message.kind == protocol::TopicKind::V2Status;
  result.accepted = is_status
                        ? registry.accept_status(message.robot_id, message.message.status, message.received)
                        : registry.accept_observation(message.robot_id, message.protocol(),
                                                      message.message.observation, message.received);
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
