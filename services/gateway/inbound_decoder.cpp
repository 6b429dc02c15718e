// InboundDecoder: parse_topic + decode_message, then the registry decides what the message means.
#include "gateway/inbound_decoder.hpp"

namespace slam::gateway {

bool InboundDecoder::decode(std::string_view topic, std::span<const std::uint8_t> payload) {
  robot_id_ = {};
  accepted_ = {};
  protocol::ParsedTopic parsed;
  status_ = protocol::parse_topic(topic, parsed);
  if (!status_) return false;
  robot_id_ = parsed.robot_id;
  status_ = protocol::decode_message(parsed.kind, payload, limits_, message_);
  return status_.is_ok();
}

InboundKind InboundDecoder::apply(RobotRegistry& registry, Instant now) {
  if (!status_) {
    if (!robot_id_.empty()) registry.count_rejected(robot_id_);
    return InboundKind::Rejected;
  }
  const bool is_status = message_.kind == protocol::TopicKind::V2Status;
  accepted_ = is_status ? registry.accept_status(robot_id_, message_.status, now)
                        : registry.accept_observation(robot_id_, protocol(), message_.observation, now);
  switch (accepted_.kind) {
    case AcceptResult::Kind::Accepted:
      return is_status ? InboundKind::Status : InboundKind::Observation;
    case AcceptResult::Kind::NoPose:
      status_ = {protocol::RejectReason::MissingField,
                 "points message without pose, and no earlier pose from this robot to cast rays from"};
      registry.count_rejected(robot_id_);
      return InboundKind::Rejected;
    case AcceptResult::Kind::RegistryFull:
      break;
  }
  return InboundKind::Refused;
}

}  // namespace slam::gateway
