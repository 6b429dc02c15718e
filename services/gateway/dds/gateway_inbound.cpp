// GatewayNode, MQTT -> DDS: the hot path. The MQTT receive thread records the traffic, decodes into
// reused buffers and queues the message; the loop records it in the registry and appends the
// observation to the batch, written when full, before an observation that would overflow it, or when
// its oldest observation has waited --batch-ms. A rejected message only touches counters and a
// rate-limited log line.
#include <string>

#include "common/core/clock.hpp"
#include "gateway/dds/gateway_msgs.hpp"
#include "gateway/dds/gateway_node.hpp"
#include "protocol/text_check.hpp"

namespace slam::gateway {

void GatewayNode::on_mqtt_message(std::string_view topic, std::span<const std::uint8_t> payload) {
  const Instant now{now_ns(), monotonic_ns()};
  bump(metrics_.messages_in);
  if (!traffic_.push(TrafficDirection::Inbound, topic, payload, now.wall_ns, now.mono_ns)) {
    bump(metrics_.traffic_dropped);
  }
  decoder_.decode(topic, payload, now, received_);
  intake_.push(received_);
}

void GatewayNode::take_inbound(InboundMessage& message) {
  const InboundResult result = apply_inbound(registry_, message);
  const AcceptResult& accepted = result.accepted;
  if (accepted.first_seen || accepted.came_online || accepted.went_offline) {
    presence_changed_ = true;
    log_presence(message, accepted);
  }
  if (message.is_vda && (result.kind == InboundKind::Observation || result.kind == InboundKind::Status))
    take_vda(message);
  switch (result.kind) {
    case InboundKind::Observation:
      if (const std::uint32_t errors = message.message.observation.error_beams; errors > 0) {
        bump(metrics_.scan_error_beams, errors);
      }
      digest_.add_hits(message.robot_id, message.message.observation.hits, message.received.wall_ns);
      batch_observation(message, accepted);
      return;
    case InboundKind::Status:
      bump(metrics_.statuses);
      return;
    case InboundKind::Rejected:
      bump(*metrics_.rejected[static_cast<size_t>(message.status.reason())]);
      log_rejection(message);
      return;
    case InboundKind::Refused:
      bump(metrics_.robots_refused);
      warn("refused", "message from new robot '" + protocol::escape_for_log(message.robot_id) +
                          "' ignored: " + std::to_string(options_.max_robots) +
                          " robots known already (max-robots)");
      return;
  }
}

// On the batch's clock, the messages' receive times: a message that arrives after the oldest one
// has waited --batch-ms sends the batch, however late the loop takes it.
void GatewayNode::batch_observation(const InboundMessage& message, const AcceptResult& accepted) {
  const protocol::DecodedObservation& observation = message.message.observation;
  const std::size_t points = observation.hits.size() + observation.misses.size();
  if (!batch_policy_.fits(points)) write_batch();
  fill_observation(message.robot_id, accepted.seq, message.received.wall_ns, message.protocol(), observation,
                   append_observation(batch_, spare_observations_));
  const std::int64_t at = message.received.mono_ns;
  if (batch_policy_.add(points, at) || batch_policy_.due(at)) write_batch();
}

void GatewayNode::write_batch() {
  const auto count = static_cast<int64_t>(batch_.observations().size());
  batch_.batch_seq(batch_.batch_seq() + 1);
  if (observation_writer_->write(batch_)) {
    bump(metrics_.observations, count);
    bump(metrics_.observation_batches);
  } else {
    bump(metrics_.write_failures);
  }
  recycle_observations(batch_, spare_observations_);
  batch_policy_.written();
}

GatewayNode::Clock::time_point GatewayNode::batch_due() const {
  return Clock::time_point(std::chrono::nanoseconds(batch_policy_.due_ns()));
}

InboundWake GatewayNode::inbound_wake() const {
  if (batch_policy_.empty()) return {};  // the first message arms the batch's deadline
  return {batch_policy_.observations_left(), batch_policy_.points_left()};
}

void GatewayNode::log_rejection(const InboundMessage& message) {
  const std::string_view reason = protocol::reason_name(message.status.reason());
  const std::string_view id = message.robot_id;
  // Keyed by robot and reason; without a valid robot id the key must not include the untrusted
  // topic, or a flood of made-up topics would get a line each. The budget caps all robots together.
  std::string key = id.empty() ? std::string("?") : std::string(id);
  key += ':';
  key += reason;
  const std::optional<std::string> tail = warnings_.admit(key);
  if (!tail || !reject_log_budget_.take(message.received.mono_ns)) return;
  const std::string who =
      id.empty() ? "message" : "message from robot '" + protocol::escape_for_log(id) + "'";
  spdlog::warn("rejected {} on '{}': {}{}", who, protocol::escape_for_log(message.topic),
               message.status.message(), *tail);
}

void GatewayNode::log_presence(const InboundMessage& message, const AcceptResult& result) {
  const std::string id = protocol::escape_for_log(message.robot_id);
  const std::string_view protocol = protocol_name(message.protocol());
  if (result.first_seen) spdlog::info("robot '{}' first seen ({})", id, protocol);
  if (result.came_online) spdlog::info("robot '{}' online again ({})", id, protocol);
  if (result.went_offline) spdlog::info("robot '{}' offline: last will / offline status", id);
}

void GatewayNode::take_vda(const InboundMessage& message) {
  bool known = true;
  const std::optional<VdaRejection> rejection =
      vda_orders_.take_message(message.robot_id, message.vda_address(), message.vda, known);
  if (!known) bump(metrics_.robots_refused);
  if (!rejection) return;
  // Reported once per order update; the planner's next waypoint starts a new order, until the robot
  // has rejected too many: that line, once per destination, is never suppressed.
  bump(metrics_.vda_orders_rejected);
  const std::string shown = protocol::escape_for_log(message.robot_id);
  if (rejection->gave_up)
    spdlog::warn("robot '{}' {}", shown, rejection->text);
  else
    warn("vda-order:" + shown, "robot '" + shown + "' " + rejection->text);
}

}  // namespace slam::gateway
