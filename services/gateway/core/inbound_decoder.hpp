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
#include <unordered_set>
#include <vector>

#include "gateway/core/robot_registry.hpp"
#include "protocol/message_decoder.hpp"
#include "protocol/reject_reason.hpp"
#include "protocol/vda5050_codec.hpp"

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
  protocol::DecodedMessage message;  // a VDA 5050 message's pose (observation) or its status too
  protocol::CodecStatus status;      // ok, or why the message is rejected
  // A VDA 5050 message: its address (manufacturer, serialNumber) and what it says.
  bool is_vda = false;
  std::string vda_manufacturer;
  std::string vda_serial_number;
  protocol::VdaMessage vda;

  Protocol protocol() const {
    if (is_vda) return Protocol::Vda5050;
    return protocol::is_v1(message.kind) ? Protocol::V1 : Protocol::V2;
  }
  protocol::VdaAddress vda_address() const { return {vda.topic, vda_manufacturer, vda_serial_number}; }
  // Obstacle points (hits and misses) of a decoded observation; 0 for anything else.
  std::size_t points() const;
};

// Which VDA 5050 robots the gateway serves as fleet control (docs/protocol.md, "VDA 5050").
struct VdaInbound {
  bool enabled = false;
  protocol::VdaTree tree;
  // "<manufacturer>/<serialNumber>" of each VDA robot; empty: any robot publishing under the tree.
  std::vector<std::string> robots;
};

class InboundDecoder {
 public:
  explicit InboundDecoder(const protocol::CodecLimits& limits, VdaInbound vda = {});

  // MQTT thread: parses `topic` and decodes `payload` into `out` (every field replaced). False when
  // the message is rejected (out.status says why).
  bool decode(std::string_view topic, std::span<const std::uint8_t> payload, Instant received,
              InboundMessage& out) const;

 private:
  // A topic under the VDA tree: the robot's address, id and message.
  bool decode_vda(std::string_view topic, std::span<const std::uint8_t> payload, InboundMessage& out) const;

  protocol::CodecLimits limits_;
  VdaInbound vda_;
  std::string vda_prefix_;  // "<interface>/"
  std::unordered_set<std::string> vda_robots_;
};

// What recording a message did.
struct InboundResult {
  InboundKind kind = InboundKind::Rejected;
  AcceptResult accepted;  // meaningful for Observation and Status
};

// Loop: records a decoded message in `registry`, or counts its rejection against the robot. A v2
// points message without a pose may still be rejected here (missing_field, set in message.status).
// A VDA 5050 state or visualization with an initialised position is an observation (the pose), one
// without a status; a connection is a status of a known robot (CONNECTIONBROKEN and OFFLINE: offline);
// a factsheet only counts.
InboundResult apply_inbound(RobotRegistry& registry, InboundMessage& message);

}  // namespace slam::gateway
