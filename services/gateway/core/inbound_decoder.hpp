#pragma once
// One inbound MQTT message in two steps on two threads: the MQTT thread parses the topic and decodes
// the payload into an InboundMessage (decode), which goes through the GatewayIntake to the loop; the
// loop records it in the robot registry (apply_inbound), the one place that decides what the message
// means. A message's buffers are reused message after message (the intake hands spent ones back), so
// a warm gateway does not allocate on the accepting path.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "gateway/core/robot_registry.hpp"
#include "protocol/message_decoder.hpp"
#include "protocol/reject_reason.hpp"

namespace slam::gateway {

enum class InboundKind : std::uint8_t {
  Observation,  // publish a RobotObservation (seq in accepted.seq)
  Status,       // battery/state recorded; nothing to publish per message
  Rejected,     // bad input: the message's status says why; nothing reaches DDS
  Refused,      // valid, but from a new robot while the registry is full
};

// One MQTT message as the MQTT thread decoded it.
struct InboundMessage {
  std::string topic;     // as received (the rejection log names it)
  std::string robot_id;  // empty when the topic named no valid robot
  Instant received;      // when the MQTT thread took it: the robot's last-seen time and the batch's clock
  protocol::DecodedMessage message;
  protocol::CodecStatus status;  // ok, or why the message is rejected

  Protocol protocol() const { return protocol::is_v1(message.kind) ? Protocol::V1 : Protocol::V2; }
  // Obstacle points (hits and misses) of a decoded observation; 0 for anything else.
  std::size_t points() const;
};

class InboundDecoder {
 public:
  explicit InboundDecoder(const protocol::CodecLimits& limits) : limits_(limits) {}

  // MQTT thread: parses `topic` and decodes `payload` into `out` (every field replaced). False when
  // the message is rejected (out.status says why).
  bool decode(std::string_view topic, std::span<const std::uint8_t> payload, Instant received,
              InboundMessage& out) const;

 private:
  protocol::CodecLimits limits_;
};

// What recording a message did.
struct InboundResult {
  InboundKind kind = InboundKind::Rejected;
  AcceptResult accepted;  // meaningful for Observation and Status
};

// Loop: records a decoded message in `registry`, or counts its rejection against the robot. A v2
// points message without a pose may still be rejected here (missing_field, set in message.status).
InboundResult apply_inbound(RobotRegistry& registry, InboundMessage& message);

}  // namespace slam::gateway
