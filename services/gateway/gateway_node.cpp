// GatewayNode: configure, and the loop that publishes robot states and subscriptions. The MQTT
// and DDS message handlers are in gateway_inbound.cpp and gateway_outbound.cpp.
#include "gateway/gateway_node.hpp"

#include <unistd.h>

#include <algorithm>
#include <utility>

#include "common/core/clock.hpp"
#include "common/core/service_identity.hpp"
#include "gateway/gateway_msgs.hpp"
#include "protocol/text_check.hpp"

namespace slam::gateway {

namespace {

std::int64_t to_ns(double seconds) {
  return static_cast<std::int64_t>(seconds * 1e9);
}

// Without sharing, no warm-up: a lone gateway sends waypoints from its start.
OwnershipConfig ownership_config(const GatewayOptions& o) {
  const std::int64_t timeout = to_ns(o.peer_timeout_s);
  // Longer than a heartbeat period past the timeout: by then every live peer has heard this
  // gateway's heartbeats (discovery included) and dropped the robots it takes.
  return {timeout, o.share ? timeout + to_ns(2.0 * kGatewayHeartbeatPeriodS) : 0};
}

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
      write_failures(c.get("write_failures")),
      commands_not_owned(c.get("commands_not_owned")),
      mqtt_requests_not_owned(c.get("mqtt_requests_not_owned")),
      robots_owned(c.get("robots_owned")),
      gateways_live(c.get("gateways_live")),
      robot_protocols_refused(c.get("robot_protocols_refused")),
      robots_forgotten(c.get("robots_forgotten")),
      fleet_digests(c.get("fleet_digests")),
      observation_batches(c.get("observation_batches")),
      scan_error_beams(c.get("scan_error_beams")) {
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
      digest_(options.digest_points_per_robot),
      corrections_(options.max_robots),
      decoder_(options.limits),
      // --batch-ms 0: every observation in a sample of its own.
      batch_policy_(options.batch_ms > 0.0
                        ? BatchLimits{.max_wait_ns = static_cast<std::int64_t>(options.batch_ms * 1e6)}
                        : BatchLimits{.max_observations = 1, .max_wait_ns = 0}),
      encoder_(options.limits),
      // The instance id this process's heartbeats carry (host:pid), so peers and self agree.
      ownership_(ServiceIdentity::of("gateway").instance_id, monotonic_ns(), ownership_config(options)),
      protocols_(options.max_robots) {}

GatewayNode::~GatewayNode() {
  // The members' own order (readers, then the MQTT client), with the last batch written before the
  // writers go.
  forget_reader_.reset();
  state_reader_.reset();
  heartbeat_reader_.reset();
  request_reader_.reset();
  waypoint_reader_.reset();
  correction_reader_.reset();
  mqtt_.reset();
  std::lock_guard inbound(inbound_mutex_);
  if (observation_writer_ && !batch_policy_.empty()) write_batch();
}

Result<std::unique_ptr<GatewayNode>> GatewayNode::create(const GatewayOptions& options, Counters& counters) {
  std::unique_ptr<GatewayNode> node(new GatewayNode(options, counters));
  SLAM_TRY(node->configure());
  return node;
}

Status GatewayNode::configure() {
  auto participant = dds::Participant::create(options_.service.domain, "slam-gateway");
  if (!participant) return participant.error();
  participant_ = std::move(*participant);

  auto observations = dds::make_writer(*participant_, dds::kRobotObservations);
  if (!observations) return observations.error();
  observation_writer_ = std::move(*observations);
  set_text(batch_.gateway_id(), ownership_.self());
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
  auto digests = dds::make_writer(*participant_, dds::kFleetDigest);
  if (!digests) return digests.error();
  digest_writer_ = std::move(*digests);
  auto points = dds::make_writer(*participant_, dds::kFleetPoints);
  if (!points) return points.error();
  points_writer_ = std::move(*points);
  auto traffic = TrafficPublisher::start(*participant_, traffic_, metrics_.write_failures);
  if (!traffic) return traffic.error();
  traffic_publisher_ = std::move(*traffic);

  mqtt::ConnectionOptions connection = options_.mqtt;
  if (connection.client_id.empty()) connection.client_id = default_client_id();
  connection.subscriptions = subscribed_filters(options_);
  const std::string client_id = connection.client_id;
  mqtt::Callbacks callbacks;
  callbacks.message = [this](std::string_view topic, std::span<const std::uint8_t> payload) {
    on_mqtt_message(topic, payload);
  };
  auto mqtt = mqtt::Connection::create(std::move(connection), std::move(callbacks));
  if (!mqtt) return mqtt.error();
  mqtt_ = std::move(*mqtt);

  // Readers last: their callbacks publish through the MQTT client (or, for corrections, mark the
  // robot for its next state, and waypoints need them). Heartbeats and states before waypoints, which need
  // both.
  if (options_.share) {
    auto heartbeats = dds::make_reader(*participant_, dds::kHeartbeat,
                                       [this](const slam::Heartbeat& h, const auto&) { on_heartbeat(h); });
    if (!heartbeats) return heartbeats.error();
    heartbeat_reader_ = std::move(*heartbeats);
  }
  auto robot_states = dds::make_reader(*participant_, dds::kRobotState,
                                       [this](const slam::RobotState& s, const auto&) { on_robot_state(s); });
  if (!robot_states) return robot_states.error();
  state_reader_ = std::move(*robot_states);
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
  auto forgets = dds::make_reader(*participant_, dds::kForgetRobot,
                                  [this](const slam::ForgetRobot& f, const auto&) { on_forget(f); });
  if (!forgets) return forgets.error();
  forget_reader_ = std::move(*forgets);

  spdlog::info("gateway ready on domain {}: broker {} as '{}', QoS {}, {} session, {} filter(s)",
               options_.service.domain, options_.mqtt.broker, client_id, options_.mqtt.qos,
               options_.mqtt.persistent_session ? "persistent" : "clean", options_.mqtt.subscriptions.size());
  if (options_.share) {
    spdlog::info("gateway '{}' shares the robots in group '{}'; it sends waypoints after a {:.1f} s warm-up",
                 ownership_.self(), options_.share_group,
                 static_cast<double>(ownership_config(options_).warmup_ns) * 1e-9);
  }
  return Status::ok();
}

void GatewayNode::run_once() {
  Instant now{};
  size_t online = 0;
  bool flush_batch = false;
  changed_.clear();
  went_offline_.clear();
  forgotten_.clear();
  {
    std::unique_lock lock(registry_mutex_);
    const auto steady_now = std::chrono::steady_clock::now();
    const auto digest_due = std::chrono::steady_clock::time_point(
        std::chrono::nanoseconds(std::min(next_digest_ns_, next_points_ns_)));
    const auto states_due_at =
        std::chrono::steady_clock::time_point(std::chrono::nanoseconds(next_states_ns_));
    const auto wake = std::min(
        {std::max(steady_now, states_due_at), mqtt_->next_attempt(), std::max(steady_now, digest_due)});
    // The MQTT thread arms a new batch's deadline and notifies: sleep on to the earlier time then.
    for (;;) {
      auto until = wake;
      if (batch_due_ns_ != 0)
        until =
            std::min(until, std::chrono::steady_clock::time_point(std::chrono::nanoseconds(batch_due_ns_)));
      if (urgent_ || std::chrono::steady_clock::now() >= until) break;
      loop_wake_.wait_until(lock, until);
    }
    const bool urgent = urgent_;
    urgent_ = false;
    now = {now_ns(), monotonic_ns()};
    flush_batch = batch_due_ns_ != 0 && now.mono_ns >= batch_due_ns_;
    if (flush_batch) batch_due_ns_ = 0;
    // Before take_changed: a forgotten robot's state must not go out after its disposal.
    for (const std::string& id : forget_) {
      const RobotRecord* r = registry_.find(id);
      if (r == nullptr) continue;
      forgotten_.emplace_back(id, r->has_pose);
      registry_.forget(id);
      digest_.forget(id);
    }
    forget_.clear();
    registry_.expire(now, [&](const RobotRecord& r) { went_offline_.push_back(r.id); });
    // The digest and MQTT wakes come more often than the state period; states wait for it, except
    // the robots whose presence changed (a first sighting, online again, offline), which go at once
    // and alone.
    if (now.mono_ns >= next_states_ns_) {
      registry_.take_changed([&](const RobotRecord& r) { changed_.push_back(r); });
      next_states_ns_ = now.mono_ns + std::chrono::nanoseconds(period_).count();
    } else if (urgent || !went_offline_.empty()) {
      registry_.take_changed([&](const RobotRecord& r) { changed_.push_back(r); }, true);
    }
    online = registry_.online();
  }
  for (const std::string& id : went_offline_) {
    spdlog::info("robot '{}' offline: silent for {} s", protocol::escape_for_log(id),
                 options_.offline_after_s);
  }
  if (flush_batch) flush_batch_when_due(now.mono_ns);
  mqtt_->poll(std::chrono::steady_clock::now());
  update_ownership(now.mono_ns);
  dispose_forgotten();
  publish_states();
  publish_digests(now.mono_ns, now.wall_ns);
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
  // Not urgent: the next digest (a tenth of a second) carries the new map pose to every reader
  // that follows motion; the robot's state record follows at its period. With a correction per
  // keyframe, waking for each would publish every robot's state many times a second.
  std::lock_guard lock(registry_mutex_);
  registry_.mark_changed(id);
}

void GatewayNode::on_forget(const slam::ForgetRobot& command) {
  const std::string id = command.robot_id().to_string();
  {
    std::lock_guard lock(protocols_mutex_);
    protocols_.forget(id);
  }
  {
    std::lock_guard lock(registry_mutex_);
    forget_.push_back(id);
    urgent_ = true;
  }
  loop_wake_.notify_one();
}

void GatewayNode::dispose_forgotten() {
  for (const auto& [id, had_pose] : forgotten_) {
    slam::RobotState state;
    state.robot_id(id);
    if (!state_writer_->dispose(state)) bump(metrics_.write_failures);
    slam::RobotOdometry odometry;
    odometry.robot_id(id);
    if (had_pose && !odometry_writer_->dispose(odometry)) bump(metrics_.write_failures);
    bump(metrics_.robots_forgotten);
    spdlog::info("robot '{}' forgotten by the operator", protocol::escape_for_log(id));
  }
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

void GatewayNode::publish_digests(std::int64_t now_mono_ns, std::int64_t now_wall_ns) {
  const bool robots_due = now_mono_ns >= next_digest_ns_;
  const bool points_due = now_mono_ns >= next_points_ns_;
  if (!robots_due && !points_due) return;
  {
    std::lock_guard lock(registry_mutex_);
    if (robots_due) digest_.collect(registry_);
    if (points_due) digest_.take_points();
  }
  {
    std::lock_guard lock(corrections_mutex_);
    if (robots_due) digest_.place_robots(corrections_);
    if (points_due) digest_.place_points(corrections_);
  }
  if (robots_due) {
    next_digest_ns_ = now_mono_ns + to_ns(options_.digest_period_s);
    fill_digest(ownership_.self(), now_wall_ns, digest_.robots(), fleet_digest_);
    bump(digest_writer_->write(fleet_digest_) ? metrics_.fleet_digests : metrics_.write_failures);
  }
  if (points_due) {
    next_points_ns_ = now_mono_ns + to_ns(options_.digest_points_period_s);
    fill_points(ownership_.self(), now_wall_ns, digest_.points(), fleet_points_);
    if (!points_writer_->write(fleet_points_)) bump(metrics_.write_failures);
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

void GatewayNode::on_heartbeat(const slam::Heartbeat& heartbeat) {
  if (text_of(heartbeat.service()) != "gateway") return;
  const std::string_view instance = text_of(heartbeat.instance_id());
  std::lock_guard lock(ownership_mutex_);
  // A stopping gateway stopped sending before saying so (on_waypoint checks shutdown_requested()).
  ownership_.observe(instance, heartbeat.state() == SERVICE_STOPPING, monotonic_ns());
}

void GatewayNode::on_robot_state(const slam::RobotState& state) {
  const LearntProtocol report{state.protocol() == slam::PROTOCOL_V1 ? Protocol::V1 : Protocol::V2,
                              state.last_seen_ns()};
  bool stored = false;
  {
    std::lock_guard lock(protocols_mutex_);
    stored = protocols_.learn(text_of(state.robot_id()), report);
  }
  if (!stored) bump(metrics_.robot_protocols_refused);
}

std::optional<Protocol> GatewayNode::protocol_of(std::string_view id) {
  std::optional<LearntProtocol> local;
  {
    std::lock_guard lock(registry_mutex_);
    if (const RobotRecord* r = registry_.find(id)) local = LearntProtocol{r->protocol, r->last_seen_ns};
  }
  std::optional<LearntProtocol> reported;
  {
    std::lock_guard lock(protocols_mutex_);
    reported = protocols_.find(id);
  }
  const auto chosen = fresher(local, reported);
  if (!chosen) return std::nullopt;
  return chosen->protocol;
}

void GatewayNode::update_ownership(std::int64_t now_mono_ns) {
  std::uint64_t version = 0;
  std::vector<std::string> live;
  gone_.clear();
  {
    std::lock_guard lock(ownership_mutex_);
    ownership_.expire(now_mono_ns, &gone_);
    version = ownership_.version();
    if (version != ownership_version_) live = ownership_.live();
  }
  for (const std::string& id : gone_) {
    spdlog::warn("gateway '{}' silent for {} s: its robots move to the others", protocol::escape_for_log(id),
                 options_.peer_timeout_s);
  }
  const bool changed = version != ownership_version_;
  if (changed) {
    ownership_version_ = version;
    std::string ids;
    for (const std::string& id : live) {
      if (!ids.empty()) ids += ", ";
      ids += protocol::escape_for_log(id);
    }
    if (options_.share) spdlog::info("gateways sharing the robots: {} ({})", live.size(), ids);
    metrics_.gateways_live.store(static_cast<int64_t>(live.size()), std::memory_order_relaxed);
  }
  // Robots owned, among every robot any gateway reported: a gauge, refreshed once a second.
  if (!changed && now_mono_ns < next_owned_count_ns_) return;
  next_owned_count_ns_ = now_mono_ns + 1'000'000'000;
  std::vector<std::string> ids;
  {
    std::lock_guard lock(protocols_mutex_);
    ids.reserve(protocols_.size());
    protocols_.for_each_id([&](const std::string& id) { ids.push_back(id); });
  }
  int64_t owned = 0;
  {
    std::lock_guard lock(ownership_mutex_);
    for (const std::string& id : ids) owned += ownership_.owns(id, now_mono_ns) ? 1 : 0;
  }
  metrics_.robots_owned.store(owned, std::memory_order_relaxed);
}

void GatewayNode::warn(const std::string& key, const std::string& line) {
  warnings_.warn(key, "{}", line);
}

}  // namespace slam::gateway
