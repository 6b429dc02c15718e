#pragma once
// One inbound MQTT message through topic parsing, payload decoding and the robot registry, in two
// steps so the node holds its registry lock only for the second. Buffers are reused message after
// message, so a warm decoder does not allocate on the accepting path. One decoder per thread.
#include <cstdint>
#include <span>
#include <string_view>

#include "gateway/robot_registry.hpp"
#include "protocol/message_decoder.hpp"
#include "protocol/reject_reason.hpp"

namespace slam::gateway {

enum class InboundKind : std::uint8_t {
  Observation,  // publish a RobotObservation (seq in accepted().seq)
  Status,       // battery/state recorded; nothing to publish per message
  Rejected,     // bad input: rejection() says why; nothing reaches DDS
  Refused,      // valid, but from a new robot while the registry is full
};

class InboundDecoder {
 public:
  explicit InboundDecoder(const protocol::CodecLimits& limits) : limits_(limits) {}

  // Step 1 (no lock): parses `topic` and decodes `payload`. False when the message is rejected.
  // robot_id() points into `topic`: keep the topic alive until apply() and the reads are done.
  bool decode(std::string_view topic, std::span<const std::uint8_t> payload);
  // Step 2 (registry lock held): records the decoded message, or counts the rejection against
  // the robot. A v2 points message without a pose may still be rejected here (missing_field).
  InboundKind apply(RobotRegistry& registry, Instant now);

  std::string_view robot_id() const { return robot_id_; }  // empty when the topic named no valid robot
  Protocol protocol() const { return protocol::is_v1(message_.kind) ? Protocol::V1 : Protocol::V2; }
  const protocol::DecodedObservation& observation() const { return message_.observation; }
  const protocol::DecodedStatus& status() const { return message_.status; }
  const protocol::CodecStatus& rejection() const { return status_; }
  const AcceptResult& accepted() const { return accepted_; }

 private:
  protocol::CodecLimits limits_;
  protocol::DecodedMessage message_;
  protocol::CodecStatus status_;
  std::string_view robot_id_;
  AcceptResult accepted_;
};

}  // namespace slam::gateway
