// GatewayNode, DDS -> MQTT: waypoint commands in each robot's odometry frame and protocol, and the
// viewer's raw MQTT requests (sent as given), each answered with an MqttReply. Runs on the loop, which
// the intake wakes for them; publishing only queues in the MQTT client, so nothing here blocks on the
// network.
#include <string>

#include "common/core/clock.hpp"
#include "common/core/shutdown.hpp"
#include "gateway/core/topic_filter.hpp"
#include "gateway/dds/gateway_msgs.hpp"
#include "gateway/dds/gateway_node.hpp"
#include "protocol/text_check.hpp"

namespace slam::gateway {

namespace {

std::span<const std::uint8_t> bytes(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

const char* kind_name(RequestKind kind) {
  switch (kind) {
    case RequestKind::Publish:
      return "publish";
    case RequestKind::Subscribe:
      return "subscribe";
    case RequestKind::Unsubscribe:
      return "unsubscribe";
  }
  return "unknown";
}

}  // namespace

Status GatewayNode::publish_mqtt(const std::string& topic, std::span<const std::uint8_t> payload, int qos,
                                 bool retain) {
  if (auto s = mqtt_->publish(topic, payload, qos, retain); !s) {
    bump(metrics_.publish_failures);
    return s;
  }
  bump(metrics_.messages_out);
  if (!traffic_.push(TrafficDirection::Outbound, topic, payload, now_ns(), monotonic_ns())) {
    bump(metrics_.traffic_dropped);
  }
  return Status::ok();
}

void GatewayNode::send_waypoint(const WaypointInput& command, const Tick& now) {
  bump(metrics_.commands);
  const std::string_view id = command.robot_id;
  // Every gateway receives every command; only the robot's owner sends it. A stopping gateway
  // sends nothing more: its STOPPING heartbeat hands its robots to the others at once.
  if (shutdown_requested() || !ownership_.owns(id, now.instant.mono_ns)) {
    bump(metrics_.commands_not_owned);
    return;
  }
  // A VDA 5050 robot this gateway has heard is one whatever the RobotStates say (they show it as v2).
  const std::optional<Protocol> protocol = vda_orders_.knows(id) ? Protocol::Vda5050 : protocol_of(id);
  const std::string shown = protocol::escape_for_log(id);
  if (!protocol || (*protocol == Protocol::Vda5050 && !vda_orders_.knows(id))) {
    bump(metrics_.commands_unknown_robot);
    warn("unknown-robot:" + shown,
         "waypoint for robot '" + shown +
             "' not sent: no valid message from it yet, so its protocol is unknown");
    return;
  }

  const Correction correction = corrections_.of(id);
  remaining_ = command.remaining;
  const protocol::Point waypoint = command.waypoint;
  std::optional<protocol::Point> position;
  if (const RobotRecord* r = registry_.find(id); r && r->has_pose) position = protocol::Point{r->x, r->y};
  const protocol::CodecStatus encoded =
      *protocol == Protocol::Vda5050
          ? encoder_.encode_vda(vda_orders_, id, correction.map_from_odom, waypoint, remaining_, position,
                                now.instant, commands_)
          : encoder_.encode(id, *protocol, command.seq, correction.map_from_odom, waypoint, remaining_,
                            commands_);
  if (!encoded) {
    // Never wrapped or clamped: a v1 robot would drive somewhere else entirely.
    bump(metrics_.commands_failed);
    warn("command:" + shown, "waypoint " + std::to_string(command.seq) + " (" + std::to_string(waypoint.x) +
                                 ", " + std::to_string(waypoint.y) + ") m (map frame) for robot '" + shown +
                                 "' (" + std::string(protocol_name(*protocol)) +
                                 ") not sent: " + encoded.message());
    return;
  }
  if (commands_.count == 0) return;  // a VDA robot's cancel under way, held already, or nothing to hold
  for (const OutboundMessage& m : commands_.view()) {
    if (auto s = publish_mqtt(m.topic, bytes(m.payload), options_.mqtt.qos, false); !s) {
      warn("publish", "waypoint for robot '" + shown + "' not sent: " + s.message());
      return;
    }
  }
  bump(metrics_.commands_sent);
}

void GatewayNode::resend_vda(const Tick& now) {
  vda_orders_.resend(now.instant, vda_resends_, vda_given_up_);
  for (const OutboundMessage& m : vda_resends_) {
    bump(metrics_.vda_resent);
    if (auto s = publish_mqtt(m.topic, bytes(m.payload), options_.mqtt.qos, false); !s)
      warn("publish", "'" + protocol::escape_for_log(m.topic) + "' not sent again: " + s.message());
  }
  for (const std::string& line : vda_given_up_) {
    bump(metrics_.vda_given_up);
    spdlog::warn("{}", line);
  }
}

std::optional<Protocol> GatewayNode::protocol_of(std::string_view id) const {
  std::optional<LearntProtocol> local;
  if (const RobotRecord* r = registry_.find(id)) local = LearntProtocol{r->protocol, r->last_seen_ns};
  const auto chosen = fresher(local, protocols_.find(id));
  if (!chosen) return std::nullopt;
  return chosen->protocol;
}

void GatewayNode::answer_request(const MqttRequestInput& request, const Tick& now) {
  // Every gateway receives every request; only the owner of its id executes and answers it (a
  // publish must reach the broker once). Unanswered during a takeover, the requester retries.
  if (shutdown_requested() || !ownership_.owns(std::to_string(request.request_id), now.instant.mono_ns)) {
    bump(metrics_.mqtt_requests_not_owned);
    return;
  }
  // A requester's retry: published or subscribed once, answered again from the cache.
  if (auto verdict = replies_sent_.admit(request.request_id); verdict.admission != Admission::Execute) {
    bump(metrics_.mqtt_requests_repeated);
    if (verdict.reply) reply(request.request_id, *verdict.reply);
    return;
  }
  bump(metrics_.mqtt_requests);
  const std::string topic = protocol::escape_for_log(request.topic, 256);
  const Status result = execute(request);
  reply(request.request_id, result);
  if (!result) {
    bump(metrics_.mqtt_requests_failed);
    warn("request", "MQTT request " + std::to_string(request.request_id) + " (" + kind_name(request.kind) +
                        " '" + topic + "') refused: " + result.message());
    return;
  }
  spdlog::info("MQTT request {}: {} '{}'", request.request_id, kind_name(request.kind), topic);
}

void GatewayNode::reply(std::uint64_t request_id, const Status& result) {
  replies_sent_.complete(request_id, result);
  slam::MqttReply sample;
  sample.request_id(request_id);
  sample.ok(static_cast<bool>(result));
  if (!result) set_text(sample.message(), result.message());
  if (!reply_writer_->write(sample)) bump(metrics_.write_failures);
}

Status GatewayNode::execute(const MqttRequestInput& request) {
  const std::string& topic = request.topic;
  if (request.qos > 2) return Error{"qos " + std::to_string(request.qos) + " is not 0, 1 or 2"};
  const int qos = static_cast<int>(request.qos);
  switch (request.kind) {
    case RequestKind::Publish:
      if (auto s = validate_topic_name(topic); !s) return s;
      return publish_mqtt(topic, request.payload, qos, request.retain);
    case RequestKind::Subscribe:
      if (auto s = validate_filter(topic); !s) return s;
      return mqtt_->subscribe(topic, qos);
    case RequestKind::Unsubscribe:
      if (auto s = validate_filter(topic); !s) return s;
      return mqtt_->unsubscribe(topic);
  }
  return Error{"unknown request kind " + std::to_string(static_cast<std::uint32_t>(request.kind))};
}

}  // namespace slam::gateway
