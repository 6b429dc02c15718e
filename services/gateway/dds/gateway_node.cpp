// GatewayNode: configure, the DDS readers (each only copies its sample into the intake), and the loop
// pass: wait, take the intake's inputs, then robot states, digests, ownership and subscriptions. What
// the loop does with MQTT messages is in gateway_inbound.cpp, with waypoints and requests in
// gateway_outbound.cpp.
#include "gateway/dds/gateway_node.hpp"

#include <unistd.h>

#include <algorithm>
#include <utility>

#include "common/core/clock.hpp"
#include "common/core/service_identity.hpp"
#include "gateway/dds/gateway_msgs.hpp"
#include "protocol/text_check.hpp"

namespace slam::gateway {

namespace {

std::int64_t to_ns(double seconds) {
  return static_cast<std::int64_t>(seconds * 1e9);
}

std::chrono::steady_clock::duration period(double seconds) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::nanoseconds(to_ns(seconds)));
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
      scan_error_beams(c.get("scan_error_beams")),
      vda_orders_rejected(c.get("vda_orders_rejected")),
      vda_resent(c.get("vda_resent")),
      vda_given_up(c.get("vda_given_up")) {
  for (protocol::RejectReason r : protocol::kAllRejectReasons) {
    rejected[static_cast<size_t>(r)] = &c.get(std::string(protocol::reason_counter(r)));
  }
}

GatewayNode::Tick GatewayNode::Tick::now() {
  const Clock::time_point at = Clock::now();
  return {at,
          {now_ns(), std::chrono::duration_cast<std::chrono::nanoseconds>(at.time_since_epoch()).count()}};
}

GatewayNode::GatewayNode(const GatewayOptions& options, Counters& counters)
    : options_(options),
      state_period_(std::max<Clock::duration>(
          std::chrono::milliseconds(1),
          std::chrono::milliseconds(static_cast<int64_t>(options.state_period_s * 1000.0)))),
      digest_period_(period(options.digest_period_s)),
      points_period_(period(options.digest_points_period_s)),
      metrics_(counters),
      traffic_(options.traffic_queue, options.traffic_rate),
      decoder_(options.limits, VdaInbound{options.vda5050, options.vda_tree, options.vda_robots}),
      registry_(RegistryConfig{static_cast<int64_t>(options.offline_after_s * 1e9), options.max_robots}),
      digest_(options.digest_points_per_robot),
      corrections_(options.max_robots),
      protocols_(options.max_robots),
      // The instance id this process's heartbeats carry (host:pid), so peers and self agree.
      ownership_(ServiceIdentity::of("gateway").instance_id, monotonic_ns(), ownership_config(options)),
      // --batch-ms 0: every observation in a sample of its own.
      batch_policy_(options.batch_ms > 0.0
                        ? BatchLimits{.max_wait_ns = static_cast<std::int64_t>(options.batch_ms * 1e6)}
                        : BatchLimits{.max_observations = 1, .max_wait_ns = 0}),
      encoder_(options.limits),
      vda_orders_(options.vda_tree, options.limits, VdaOrdersConfig{.max_robots = options.max_robots}) {}

GatewayNode::~GatewayNode() {
  // The members' own order (readers, then the MQTT client), with the last batch written before the
  // writers go.
  forget_reader_.reset();
  state_reader_.reset();
  heartbeat_reader_.reset();
  request_reader_.reset();
  waypoint_reader_.reset();
  correction_reader_.reset();
  intake_.close();  // an MQTT thread waiting for room goes on: nothing drains from here
  mqtt_.reset();
  if (!observation_writer_) return;
  intake_.drain(inputs_);
  for (InboundMessage& m : inputs_.inbound) take_inbound(m);
  if (!batch_policy_.empty()) write_batch();
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
  SLAM_TRY(make_writers());
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
  SLAM_TRY(make_readers());

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

Status GatewayNode::make_writers() {
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
  return Status::ok();
}

// Each reader copies its sample into the intake: a plain copy, never a lock the loop holds for long.
Status GatewayNode::make_readers() {
  if (options_.share) {
    auto heartbeats =
        dds::make_reader(*participant_, dds::kHeartbeat, [this](const slam::Heartbeat& h, const auto&) {
          if (text_of(h.service()) != "gateway") return;
          intake_.push(PeerHeartbeat{h.instance_id().to_string(), h.state() == SERVICE_STOPPING});
        });
    if (!heartbeats) return heartbeats.error();
    heartbeat_reader_ = std::move(*heartbeats);
  }
  auto robot_states =
      dds::make_reader(*participant_, dds::kRobotState,
                       [this](const slam::RobotState& s, const auto&) { intake_.push(to_input(s)); });
  if (!robot_states) return robot_states.error();
  state_reader_ = std::move(*robot_states);
  auto corrections =
      dds::make_reader(*participant_, dds::kPoseCorrection,
                       [this](const slam::PoseCorrection& c, const auto&) { intake_.push(to_input(c)); });
  if (!corrections) return corrections.error();
  correction_reader_ = std::move(*corrections);
  auto waypoints =
      dds::make_reader(*participant_, dds::kWaypointCommand,
                       [this](const slam::WaypointCommand& c, const auto&) { intake_.push(to_input(c)); });
  if (!waypoints) return waypoints.error();
  waypoint_reader_ = std::move(*waypoints);
  auto requests =
      dds::make_reader(*participant_, dds::kMqttRequest,
                       [this](const slam::MqttRequest& r, const auto&) { intake_.push(to_input(r)); });
  if (!requests) return requests.error();
  request_reader_ = std::move(*requests);
  auto forgets = dds::make_reader(
      *participant_, dds::kForgetRobot,
      [this](const slam::ForgetRobot& f, const auto&) { intake_.push_forget(f.robot_id().to_string()); });
  if (!forgets) return forgets.error();
  forget_reader_ = std::move(*forgets);
  return Status::ok();
}

void GatewayNode::run_once() {
  wait_for_work();
  const Tick now = Tick::now();
  presence_changed_ = false;
  take_inputs(now);
  resend_vda(now);
  if (batch_policy_.due(now.instant.mono_ns)) write_batch();
  collect_changed_robots(now);
  mqtt_->poll(now.at);
  update_ownership(now);
  dispose_forgotten();
  publish_states();
  publish_digests(now);
  metrics_.robots_online.store(static_cast<int64_t>(registry_.online()), std::memory_order_relaxed);
  metrics_.reconnects.store(static_cast<int64_t>(mqtt_->reconnects()), std::memory_order_relaxed);
  publish_subscriptions();
}

void GatewayNode::wait_for_work() {
  Clock::time_point wake = std::min({next_states_, next_digest_, next_points_, mqtt_->next_attempt()});
  if (!batch_policy_.empty()) wake = std::min(wake, batch_due());
  intake_.wait_until(wake, inbound_wake());
}

// Peers and protocols first, then corrections: the waypoints after them are sent with what they say.
// MQTT messages before the forgets, as when the MQTT thread recorded them on arrival.
void GatewayNode::take_inputs(const Tick& now) {
  intake_.drain(inputs_);
  for (const PeerHeartbeat& h : inputs_.heartbeats)
    ownership_.observe(h.instance_id, h.stopping, now.instant.mono_ns);
  for (const ProtocolReport& p : inputs_.protocols) take_protocol(p);
  for (const CorrectionInput& c : inputs_.corrections) take_correction(c);
  for (InboundMessage& m : inputs_.inbound) take_inbound(m);
  forgotten_.clear();
  for (const std::string& id : inputs_.forgets) forget_robot(id);
  for (const WaypointInput& w : inputs_.waypoints) send_waypoint(w, now);
  for (const MqttRequestInput& r : inputs_.requests) answer_request(r, now);
}

void GatewayNode::take_protocol(const ProtocolReport& input) {
  if (!protocols_.learn(input.robot_id, input.report)) bump(metrics_.robot_protocols_refused);
}

void GatewayNode::take_correction(const CorrectionInput& input) {
  const Result<bool> changed = corrections_.update(input.robot_id, input.correction);
  if (!changed) {
    bump(metrics_.corrections_rejected);
    const std::string shown = protocol::escape_for_log(input.robot_id);
    warn("correction:" + shown, "correction " + std::to_string(input.correction.version) + " for robot '" +
                                    shown + "' ignored: " + changed.message());
    return;
  }
  bump(metrics_.corrections);
  // Not urgent: the next digest (a tenth of a second) carries the new map pose to every reader
  // that follows motion; the robot's state record follows at its period. With a correction per
  // keyframe, publishing each at once would publish every robot's state many times a second.
  if (*changed) registry_.mark_changed(input.robot_id);
}

// Before collect_changed_robots: a forgotten robot's state must not go out after its disposal.
void GatewayNode::forget_robot(const std::string& id) {
  protocols_.forget(id);
  vda_orders_.forget(id);
  presence_changed_ = true;
  const RobotRecord* r = registry_.find(id);
  if (r == nullptr) return;
  forgotten_.emplace_back(id, r->has_pose);
  registry_.forget(id);
  digest_.forget(id);
}

void GatewayNode::collect_changed_robots(const Tick& now) {
  changed_.clear();
  went_offline_.clear();
  registry_.expire(now.instant, [&](const RobotRecord& r) { went_offline_.push_back(r.id); });
  // The digest and MQTT wakes come more often than the state period; states wait for it, except
  // the robots whose presence changed (a first sighting, online again, offline), which go at once
  // and alone.
  if (now.at >= next_states_) {
    registry_.take_changed([&](const RobotRecord& r) { changed_.push_back(r); });
    next_states_ = now.at + state_period_;
  } else if (presence_changed_ || !went_offline_.empty()) {
    registry_.take_changed([&](const RobotRecord& r) { changed_.push_back(r); }, true);
  }
  for (const std::string& id : went_offline_) {
    spdlog::info("robot '{}' offline: silent for {} s", protocol::escape_for_log(id),
                 options_.offline_after_s);
  }
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
    const Correction correction = corrections_.of(r.id);
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

void GatewayNode::publish_digests(const Tick& now) {
  const bool robots_due = now.at >= next_digest_;
  const bool points_due = now.at >= next_points_;
  if (robots_due) {
    next_digest_ = now.at + digest_period_;
    digest_.collect(registry_);
    digest_.place_robots(corrections_);
    fill_digest(ownership_.self(), now.instant.wall_ns, digest_.robots(), fleet_digest_);
    bump(digest_writer_->write(fleet_digest_) ? metrics_.fleet_digests : metrics_.write_failures);
  }
  if (points_due) {
    next_points_ = now.at + points_period_;
    digest_.take_points();
    digest_.place_points(corrections_);
    fill_points(ownership_.self(), now.instant.wall_ns, digest_.points(), fleet_points_);
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

void GatewayNode::update_ownership(const Tick& now) {
  const std::int64_t now_ns = now.instant.mono_ns;
  gone_.clear();
  ownership_.expire(now_ns, &gone_);
  for (const std::string& id : gone_) {
    spdlog::warn("gateway '{}' silent for {} s: its robots move to the others", protocol::escape_for_log(id),
                 options_.peer_timeout_s);
  }
  const std::uint64_t version = ownership_.version();
  const bool changed = version != ownership_version_;
  if (changed) {
    ownership_version_ = version;
    const std::vector<std::string> live = ownership_.live();
    std::string ids;
    for (const std::string& id : live) {
      if (!ids.empty()) ids += ", ";
      ids += protocol::escape_for_log(id);
    }
    if (options_.share) spdlog::info("gateways sharing the robots: {} ({})", live.size(), ids);
    metrics_.gateways_live.store(static_cast<int64_t>(live.size()), std::memory_order_relaxed);
  }
  // Robots owned, among every robot any gateway reported: a gauge, refreshed once a second.
  if (!changed && now.at < next_owned_count_) return;
  next_owned_count_ = now.at + std::chrono::seconds(1);
  int64_t owned = 0;
  protocols_.for_each_id([&](const std::string& id) { owned += ownership_.owns(id, now_ns) ? 1 : 0; });
  metrics_.robots_owned.store(owned, std::memory_order_relaxed);
}

void GatewayNode::warn(const std::string& key, const std::string& line) {
  warnings_.warn(key, "{}", line);
}

}  // namespace slam::gateway
