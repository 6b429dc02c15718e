// GatewayNode: configure, and the loop that publishes robot states and subscriptions. The MQTT
// and DDS message handlers are in gateway_inbound.cpp and gateway_outbound.cpp.
#include "gateway/gateway_node.hpp"

#include <unistd.h>

#include <algorithm>
#include <utility>

#include "common/core/clock.hpp"
#include "gateway/gateway_msgs.hpp"
#include "protocol/text_check.hpp"

namespace slam::gateway {

namespace {

std::string default_client_id() {
  char host[256] = {};
  if (::gethostname(host, sizeof(host) - 1) != 0) host[0] = '\0';
  return "slam-gateway-" + std::string(host[0] ? host : "host") + "-" + std::to_string(::getpid());
}

}  // namespace

GatewayNode::Metrics::Metrics(Counters& c)
    : messages_in(c.get("messages_in")),
      messages_out(c.get("messages_out")),
      observations(c.get("observations")),
      statuses(c.get("statuses")),
      rejected{},
      robots_refused(c.get("robots_refused")),
      robots_online(c.get("robots_online")),
      robot_states(c.get("robot_states")),
      commands(c.get("commands")),
      commands_sent(c.get("commands_sent")),
      commands_failed(c.get("commands_failed")),
      commands_unknown_robot(c.get("commands_unknown_robot")),
      corrections(c.get("corrections")),
      corrections_rejected(c.get("corrections_rejected")),
      mqtt_requests(c.get("mqtt_requests")),
      mqtt_requests_failed(c.get("mqtt_requests_failed")),
      mqtt_requests_repeated(c.get("mqtt_requests_repeated")),
      publish_failures(c.get("publish_failures")),
      traffic_dropped(c.get("traffic_dropped")),
      reconnects(c.get("reconnects")),
      write_failures(c.get("write_failures")) {
  for (protocol::RejectReason r : protocol::kAllRejectReasons) {
    rejected[static_cast<size_t>(r)] = &c.get(std::string(protocol::reason_counter(r)));
  }
}

GatewayNode::GatewayNode(const GatewayOptions& options, Counters& counters)
    : options_(options),
      period_(std::max<int64_t>(1, static_cast<int64_t>(options.state_period_s * 1000.0))),
      metrics_(counters),
      traffic_(options.traffic_queue, options.traffic_rate),
      registry_(RegistryConfig{static_cast<int64_t>(options.offline_after_s * 1e9), options.max_robots}),
      corrections_(options.max_robots),
      decoder_(options.limits),
      encoder_(options.limits) {}

Result<std::unique_ptr<GatewayNode>> GatewayNode::create(const GatewayOptions& options, Counters& counters) {
  std::unique_ptr<GatewayNode> node(new GatewayNode(options, counters));
  SLAM_TRY(node->configure());
  return node;
}

Status GatewayNode::configure() {
  auto participant = dds::Participant::create(options_.service.domain, "slam-gateway");
  if (!participant) return participant.error();
  participant_ = std::move(*participant);

  auto observations = dds::make_writer(*participant_, dds::kRobotObservation);
  if (!observations) return observations.error();
  observation_writer_ = std::move(*observations);
  auto states = dds::make_writer(*participant_, dds::kRobotState);
  if (!states) return states.error();
  state_writer_ = std::move(*states);
  auto odometry = dds::make_writer(*participant_, dds::kRobotOdometry);
  if (!odometry) return odometry.error();
  odometry_writer_ = std::move(*odometry);
  auto subscriptions = dds::make_writer(*participant_, dds::kMqttSubscriptions);
  if (!subscriptions) return subscriptions.error();
  subscriptions_writer_ = std::move(*subscriptions);
  auto replies = dds::make_writer(*participant_, dds::kMqttReply);
  if (!replies) return replies.error();
  reply_writer_ = std::move(*replies);
  auto traffic = TrafficPublisher::start(*participant_, traffic_, metrics_.write_failures);
  if (!traffic) return traffic.error();
  traffic_publisher_ = std::move(*traffic);

  mqtt::ConnectionOptions connection = options_.mqtt;
  if (connection.client_id.empty()) connection.client_id = default_client_id();
  const std::string client_id = connection.client_id;
  mqtt::Callbacks callbacks;
  callbacks.message = [this](std::string_view topic, std::span<const std::uint8_t> payload) {
    on_mqtt_message(topic, payload);
  };
  auto mqtt = mqtt::Connection::create(std::move(connection), std::move(callbacks));
  if (!mqtt) return mqtt.error();
  mqtt_ = std::move(*mqtt);

  // Readers last: their callbacks publish through the MQTT client (or, for corrections, wake the
  // loop, and waypoints need them).
  auto corrections =
      dds::make_reader(*participant_, dds::kPoseCorrection,
                       [this](const slam::PoseCorrection& c, const auto&) { on_correction(c); });
  if (!corrections) return corrections.error();
  correction_reader_ = std::move(*corrections);
  auto waypoints = dds::make_reader(*participant_, dds::kWaypointCommand,
                                    [this](const slam::WaypointCommand& c, const auto&) { on_waypoint(c); });
  if (!waypoints) return waypoints.error();
  waypoint_reader_ = std::move(*waypoints);
  auto requests = dds::make_reader(*participant_, dds::kMqttRequest,
                                   [this](const slam::MqttRequest& r, const auto&) { on_request(r); });
  if (!requests) return requests.error();
  request_reader_ = std::move(*requests);

  spdlog::info("gateway ready on domain {}: broker {} as '{}', QoS {}, {} session, {} filter(s)",
               options_.service.domain, options_.mqtt.broker, client_id, options_.mqtt.qos,
               options_.mqtt.persistent_session ? "persistent" : "clean", options_.mqtt.subscriptions.size());
  return Status::ok();
}

void GatewayNode::run_once() {
  Instant now{};
  size_t online = 0;
  changed_.clear();
  went_offline_.clear();
  {
    std::unique_lock lock(registry_mutex_);
    const auto wake = std::min(std::chrono::steady_clock::now() + period_, mqtt_->next_attempt());
    loop_wake_.wait_until(lock, wake, [&] { return urgent_; });
    urgent_ = false;
    now = {now_ns(), monotonic_ns()};
    registry_.expire(now, [&](const RobotRecord& r) { went_offline_.push_back(r.id); });
    registry_.take_changed([&](const RobotRecord& r) { changed_.push_back(r); });
    online = registry_.online();
  }
  for (const std::string& id : went_offline_) {
    spdlog::info("robot '{}' offline: silent for {} s", protocol::escape_for_log(id),
                 options_.offline_after_s);
  }
  mqtt_->poll(std::chrono::steady_clock::now());
  publish_states();
  metrics_.robots_online.store(static_cast<int64_t>(online), std::memory_order_relaxed);
  metrics_.reconnects.store(static_cast<int64_t>(mqtt_->reconnects()), std::memory_order_relaxed);
  publish_subscriptions();
}

void GatewayNode::on_correction(const slam::PoseCorrection& sample) {
  const std::string_view id = text_of(sample.robot_id());
  Result<bool> changed = false;
  {
    std::lock_guard lock(corrections_mutex_);
    changed = corrections_.update(id, to_correction(sample));
  }
  if (!changed) {
    bump(metrics_.corrections_rejected);
    const std::string shown = protocol::escape_for_log(id);
    warn("correction:" + shown, "correction " + std::to_string(sample.version()) + " for robot '" + shown +
                                    "' ignored: " + changed.message());
    return;
  }
  bump(metrics_.corrections);
  if (!*changed) return;
  bool known = false;
  {
    std::lock_guard lock(registry_mutex_);
    known = registry_.mark_changed(id);
    if (known) urgent_ = true;
  }
  if (known) loop_wake_.notify_one();
}

void GatewayNode::publish_states() {
  for (const RobotRecord& r : changed_) {
    Correction correction;
    {
      std::lock_guard lock(corrections_mutex_);
      correction = corrections_.of(r.id);
    }
    const Pose odom_pose{r.x, r.y, r.theta};
    // A robot heard only through status messages has no pose to place in the map.
    const Pose map_pose =
        r.has_pose ? to_map_frame(correction.map_from_odom, odom_pose, r.has_heading) : odom_pose;
    fill_state(r, map_pose, state_);
    bump(state_writer_->write(state_) ? metrics_.robot_states : metrics_.write_failures);
    if (!r.has_pose) continue;
    fill_odometry(r, correction.version, odometry_);
    if (!odometry_writer_->write(odometry_)) bump(metrics_.write_failures);
  }
}

void GatewayNode::publish_subscriptions() {
  const std::uint64_t version = mqtt_->version();
  if (version == published_version_) return;
  slam::MqttSubscriptions sample;
  sample.connected(mqtt_->connected());
  set_text(sample.broker(), mqtt_->broker());
  for (const std::string& f : mqtt_->filters()) {
    sample.filters().emplace_back();
    set_text(sample.filters().back(), f);
  }
  if (subscriptions_writer_->write(sample)) {
    published_version_ = version;
  } else {
    bump(metrics_.write_failures);
  }
}

void GatewayNode::warn(const std::string& key, const std::string& line) {
  warnings_.warn(key, "{}", line);
}

}  // namespace slam::gateway
