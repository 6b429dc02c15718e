// GatewayNode, MQTT -> DDS: the hot path. Runs on paho's receive thread: traffic record, decode
// into reused buffers, registry update under a short lock, the observation appended to the batch
// (written here when full; the loop writes it when it has waited --batch-ms).
// A rejected message only touches counters and a rate-limited log line.
#include <string>

#include "common/core/clock.hpp"
#include "gateway/gateway_msgs.hpp"
#include "gateway/gateway_node.hpp"
#include "protocol/text_check.hpp"

namespace slam::gateway {

void GatewayNode::on_mqtt_message(std::string_view topic, std::span<const std::uint8_t> payload) {
  const Instant now{now_ns(), monotonic_ns()};
  bump(metrics_.messages_in);
  if (!traffic_.push(TrafficDirection::Inbound, topic, payload, now.wall_ns, now.mono_ns)) {
    bump(metrics_.traffic_dropped);
  }

  std::lock_guard inbound(inbound_mutex_);
  decoder_.decode(topic, payload);
  InboundKind kind{};
  {
    std::lock_guard lock(registry_mutex_);
    kind = decoder_.apply(registry_, now);
    if (kind == InboundKind::Observation)
      digest_.add_hits(decoder_.robot_id(), decoder_.observation().hits, now.wall_ns);
    const AcceptResult& a = decoder_.accepted();
    if (a.first_seen || a.came_online || a.went_offline) urgent_ = true;
  }
  const AcceptResult& accepted = decoder_.accepted();
  if (accepted.first_seen || accepted.came_online || accepted.went_offline) {
    loop_wake_.notify_one();
    log_presence(decoder_.robot_id(), accepted);
  }

  switch (kind) {
    case InboundKind::Observation: {
      const protocol::DecodedObservation& observation = decoder_.observation();
      if (observation.error_beams > 0) bump(metrics_.scan_error_beams, observation.error_beams);
      const std::size_t points = observation.hits.size() + observation.misses.size();
      if (!batch_policy_.fits(points)) write_batch();
      const bool first = batch_policy_.empty();
      fill_observation(decoder_.robot_id(), accepted.seq, now.wall_ns, decoder_.protocol(), observation,
                       append_observation(batch_, spare_observations_));
      if (batch_policy_.add(points, now.mono_ns) || batch_policy_.due(now.mono_ns)) {
        write_batch();
      } else if (first) {
        arm_batch_deadline();  // the loop writes it when its wait is over, unless it fills up first
      }
      return;
    }
    case InboundKind::Status:
      bump(metrics_.statuses);
      return;
    case InboundKind::Rejected:
      bump(*metrics_.rejected[static_cast<size_t>(decoder_.rejection().reason())]);
      log_rejection(topic, now);
      return;
    case InboundKind::Refused:
      bump(metrics_.robots_refused);
      warn("refused", "message from new robot '" + protocol::escape_for_log(decoder_.robot_id()) +
                          "' ignored: " + std::to_string(options_.max_robots) +
                          " robots known already (max-robots)");
      return;
  }
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

void GatewayNode::arm_batch_deadline() {
  const std::int64_t due = batch_policy_.due_ns();
  {
    std::lock_guard lock(registry_mutex_);
    // A deadline armed earlier wakes the loop first, and the loop arms this one then.
    if (batch_due_ns_ != 0 && batch_due_ns_ <= due) return;
    batch_due_ns_ = due;
  }
  loop_wake_.notify_one();
}

void GatewayNode::flush_batch_when_due(std::int64_t now_mono_ns) {
  std::lock_guard inbound(inbound_mutex_);
  if (batch_policy_.due(now_mono_ns)) {
    write_batch();
  } else if (!batch_policy_.empty()) {
    arm_batch_deadline();
  }
}

void GatewayNode::log_rejection(std::string_view topic, Instant now) {
  const protocol::CodecStatus& why = decoder_.rejection();
  const std::string_view reason = protocol::reason_name(why.reason());
  const std::string_view id = decoder_.robot_id();
  // Keyed by robot and reason; without a valid robot id the key must not include the untrusted
  // topic, or a flood of made-up topics would get a line each. The budget caps all robots together.
  std::string key = id.empty() ? std::string("?") : std::string(id);
  key += ':';
  key += reason;
  const std::optional<std::string> tail = warnings_.admit(key);
  if (!tail || !reject_log_budget_.take(now.mono_ns)) return;
  const std::string who =
      id.empty() ? "message" : "message from robot '" + protocol::escape_for_log(id) + "'";
  spdlog::warn("rejected {} on '{}': {}{}", who, protocol::escape_for_log(topic), why.message(), *tail);
}

void GatewayNode::log_presence(std::string_view robot_id, const AcceptResult& result) {
  const std::string id = protocol::escape_for_log(robot_id);
  const char* protocol = decoder_.protocol() == Protocol::V1 ? "v1" : "v2";
  if (result.first_seen) spdlog::info("robot '{}' first seen ({})", id, protocol);
  if (result.came_online) spdlog::info("robot '{}' online again ({})", id, protocol);
  if (result.went_offline) spdlog::info("robot '{}' offline: last will / offline status", id);
}

}  // namespace slam::gateway
