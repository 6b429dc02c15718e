// Robot protocol over MQTT for the simulated fleet: topics, encoding, command decoding.
#include "simulator/mqtt/robot_link.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cmath>

#include "protocol/reject_reason.hpp"
#include "protocol/robot_topics.hpp"
#include "protocol/text_check.hpp"
#include "protocol/topic.hpp"
#include "protocol/v1_codec.hpp"
#include "protocol/v1_robot_codec.hpp"
#include "protocol/v2_robot_encode.hpp"
#include "protocol/v2_server_codec.hpp"

namespace slam::sim {
namespace {

// Commands waiting for the loop; beyond this a flood is dropped (and counted) instead of growing.
constexpr size_t kMaxPendingOrders = 65'536;
// A robot's connection: a short keep-alive, and quick retries after a broker restart.
constexpr int kKeepAliveS = 10;
constexpr double kReconnectMinS = 1.0;
constexpr double kReconnectMaxS = 4.0;
// QoS 0 reports queue inside paho while the socket drains; this bounds that queue.
constexpr int kMaxBufferedMessages = 100'000;
// Ranges are sent to 0.1 mm: finer digits are noise and only lengthen every v2 scan. Dividing by
// the exact integer gives the double nearest the decimal, which prints in its short form.
constexpr double kRangeSteps = 1e4;  // per metre

std::span<const uint8_t> as_bytes(const std::string& text) {
  return {reinterpret_cast<const uint8_t*>(text.data()), text.size()};
}

}  // namespace

RobotLinks::RobotLinks(Settings settings, Counters& counters)
    : settings_(std::move(settings)),
      reports_sent_(counters.get("reports_sent")),
      reports_dropped_(counters.get("reports_dropped")),
      waypoints_received_(counters.get("waypoints_received")),
      waypoints_rejected_(counters.get("waypoints_rejected")),
      orders_dropped_(counters.get("waypoints_dropped")),
      mqtt_connected_(counters.get("mqtt_connected")),
      mqtt_reconnects_(counters.get("mqtt_reconnects")),
      mqtt_connect_failures_(counters.get("mqtt_connect_failures")) {}

Result<std::unique_ptr<RobotLinks>> RobotLinks::create(Settings settings, Counters& counters) {
  std::unique_ptr<RobotLinks> links(new RobotLinks(std::move(settings), counters));
  if (links->settings_.multiplex) {
    std::vector<std::string> filters;
    if (links->settings_.protocol == RobotProtocol::V1) {
      filters.emplace_back(protocol::kV1CommandFilter);
    } else if (links->settings_.protocol == RobotProtocol::V2) {
      filters.emplace_back(protocol::kV2WaypointFilter);
      filters.emplace_back(protocol::kV2PathFilter);
    }
    if (links->settings_.protocol == RobotProtocol::Vda5050 || links->settings_.vda_robots) {
      for (const auto topic : {protocol::VdaTopic::Order, protocol::VdaTopic::InstantActions})
        filters.push_back(protocol::vda_command_filter(links->vda_tree_, kVdaManufacturer, topic));
    }
    auto link = links->open(fmt::format("slam-simulator-{}", getpid()), std::move(filters), std::nullopt);
    if (!link) return link.error();
    links->shared_link_ = std::move(*link);
  }
  return links;
}

RobotLinks::~RobotLinks() {
  for (auto& [id, e] : endpoints_) {
    if (e.protocol == RobotProtocol::V2)
      send(e, e.status_topic, as_bytes(std::string(protocol::kV2OfflineStatus)));
    if (e.protocol == RobotProtocol::Vda5050) send_connection(e, id, protocol::VdaConnection::Offline);
  }
  // Start every disconnect before waiting on any, so a large fleet closes in one round trip.
  for (auto& [id, e] : endpoints_)
    if (e.own_link) e.own_link->begin_disconnect();
  if (shared_link_) shared_link_->begin_disconnect();
  endpoints_.clear();
  shared_link_.reset();
  mqtt_connected_.store(0, std::memory_order_relaxed);
}

Result<std::unique_ptr<mqtt::Connection>> RobotLinks::open(const std::string& client_id,
                                                           std::vector<std::string> subscriptions,
                                                           std::optional<mqtt::Will> will) {
  mqtt::ConnectionOptions options;
  options.broker = settings_.broker;
  options.tls_ca_file = settings_.tls_ca_file;
  options.client_id = client_id;
  if (!settings_.password.empty() && !settings_.multiplex) {
    options.username = client_id;  // a robot's connection is named by its robot id
    options.password = settings_.password;
  }
  options.qos = 1;
  options.subscriptions = std::move(subscriptions);
  options.will = std::move(will);
  options.keepalive_s = kKeepAliveS;
  options.reconnect_min_s = kReconnectMinS;
  options.reconnect_max_s = kReconnectMaxS;
  options.max_buffered_messages = kMaxBufferedMessages;
  mqtt::Callbacks callbacks;
  callbacks.message = [this](std::string_view topic, std::span<const uint8_t> payload) {
    on_message(topic, payload);
  };
  callbacks.connected = [this](bool reconnect) {
    if (reconnect) bump(mqtt_reconnects_);
  };
  callbacks.connect_failed = [this](const std::string&) { bump(mqtt_connect_failures_); };
  return mqtt::Connection::create(std::move(options), std::move(callbacks));
}

Status RobotLinks::add(const std::string& robot_id, std::optional<RobotProtocol> speaks) {
  if (endpoints_.contains(robot_id))
    return Error{fmt::format("robot '{}' already has a connection", robot_id)};
  Endpoint e;
  e.protocol = speaks.value_or(settings_.protocol);
  if (e.protocol == RobotProtocol::Vda5050) {
    if (settings_.multiplex && settings_.protocol != RobotProtocol::Vda5050 && !settings_.vda_robots)
      return Error{"the shared MQTT connection was opened without the VDA 5050 subscriptions"};
    std::vector<std::string> subscriptions;
    std::optional<mqtt::Will> will;
    if (auto s = add_vda(robot_id, e, subscriptions, will); !s) return s;
    return attach(robot_id, std::move(e), std::move(subscriptions), std::move(will));
  }
  if (settings_.multiplex && e.protocol != settings_.protocol)
    return Error{"the shared MQTT connection subscribes the --protocol robots' commands only"};
  const bool v1 = e.protocol == RobotProtocol::V1;
  auto s = v1 ? protocol::v1_adv_topic(robot_id, e.report_topic)
              : protocol::v2_scan_topic(robot_id, e.report_topic);
  if (s) s = protocol::v2_status_topic(robot_id, e.status_topic);
  if (!s) return Error{s.detail()};
  std::vector<std::string> subscriptions(v1 ? 1 : 2);
  if (v1) {
    s = protocol::v1_command_topic(robot_id, subscriptions[0]);
  } else {
    s = protocol::v2_waypoint_topic(robot_id, subscriptions[0]);
    if (s) s = protocol::v2_path_topic(robot_id, subscriptions[1]);
  }
  if (!s) return Error{s.detail()};
  std::optional<mqtt::Will> will;
  if (!v1) will = mqtt::Will{e.status_topic, std::string(protocol::kV2OfflineStatus)};
  return attach(robot_id, std::move(e), std::move(subscriptions), std::move(will));
}

Status RobotLinks::attach(const std::string& robot_id, Endpoint e, std::vector<std::string> subscriptions,
                          std::optional<mqtt::Will> will) {
  if (settings_.multiplex) {
    e.link = shared_link_.get();
  } else {
    auto link = open(robot_id, std::move(subscriptions), std::move(will));
    if (!link) return link.error();
    e.own_link = std::move(*link);
    e.link = e.own_link.get();
  }
  endpoints_.emplace(robot_id, std::move(e));
  return {};
}

void RobotLinks::remove(const std::string& robot_id) {
  const auto it = endpoints_.find(robot_id);
  if (it == endpoints_.end()) return;
  if (it->second.protocol == RobotProtocol::V2)
    send(it->second, it->second.status_topic, as_bytes(std::string(protocol::kV2OfflineStatus)));
  if (it->second.protocol == RobotProtocol::Vda5050)
    send_connection(it->second, robot_id, protocol::VdaConnection::Offline);
  endpoints_.erase(it);
}

void RobotLinks::send(Endpoint& e, const std::string& topic, std::span<const uint8_t> payload) {
  if (e.link->publish(topic, payload, 0, false))
    bump(reports_sent_);
  else
    bump(reports_dropped_);
}

void RobotLinks::send_status(Endpoint& e, bool driving, double time_s) {
  const auto s = protocol::encode_v2_status({driving ? "driving" : "idle", std::nullopt}, text_);
  if (!s) return;                                                           // constant states: cannot fail
  if (!e.link->publish(e.status_topic, as_bytes(text_), 0, false)) return;  // retried with the next report
  e.status_connects = e.link->connects();
  e.status_time_s = time_s;
  e.driving = driving;
}

void RobotLinks::publish(const RobotReport& report, bool driving) {
  const auto it = endpoints_.find(report.robot_id);
  if (it == endpoints_.end()) {
    bump(reports_dropped_);
    return;
  }
  Endpoint& e = it->second;
  if (e.protocol == RobotProtocol::Vda5050) {
    publish_vda(e, it->first, report, driving);
    return;
  }
  protocol::CodecStatus status;
  if (e.protocol == RobotProtocol::V1) {
    hits_.resize(report.hits.size());
    for (size_t i = 0; i < report.hits.size(); ++i) hits_[i] = {report.hits[i].x, report.hits[i].y};
    status = protocol::encode_v1_adv({report.reported_pose.x, report.reported_pose.y}, hits_,
                                     settings_.limits.units_per_meter, bytes_);
    if (status) send(e, e.report_topic, bytes_);
  } else {
    ranges_.resize(report.ranges.size());
    for (size_t i = 0; i < report.ranges.size(); ++i)
      ranges_[i] = std::round(report.ranges[i] * kRangeSteps) / kRangeSteps;
    protocol::V2Scan scan;
    scan.pose = {report.reported_pose.x, report.reported_pose.y, report.reported_pose.theta};
    scan.angles = report.angles;
    scan.ranges = ranges_;
    scan.max_range = report.max_range;
    if (report.sensor)
      scan.sensor = protocol::V2SensorOffset{report.sensor->x, report.sensor->y, report.sensor->theta};
    scan.stamp = report.time_s;  // the robot's own clock: simulated time
    status = protocol::encode_v2_scan(scan, settings_.limits, text_);
    if (status) send(e, e.report_topic, as_bytes(text_));
    if (e.link->connected() && (e.status_connects != e.link->connects() || e.driving != driving ||
                                report.time_s - e.status_time_s >= kStatusPeriodS))
      send_status(e, driving, report.time_s);
  }
  if (!status) {
    bump(reports_dropped_);
    warnings_.warn("encode", "report of '{}' not sent: {}", report.robot_id, status.message());
  }
}

void RobotLinks::poll(std::chrono::steady_clock::time_point now) {
  int64_t connected = 0;
  const auto poll_one = [&](mqtt::Connection& link) {
    link.poll(now);
    if (link.connected()) ++connected;
  };
  if (shared_link_) poll_one(*shared_link_);
  for (auto& [id, e] : endpoints_)
    if (e.own_link) poll_one(*e.own_link);
  mqtt_connected_.store(connected, std::memory_order_relaxed);
}

void RobotLinks::drain_orders(std::vector<WaypointOrder>& out) {
  out.clear();
  {
    std::lock_guard lock(intake_mutex_);
    out.swap(intake_);
    vda_commands_.swap(vda_intake_);
    vda_intake_.clear();
  }
  // A VDA robot's waypoints come from its order: those its reports reached, then the new orders'.
  out.insert(out.end(), steering_.begin(), steering_.end());
  steering_.clear();
  for (const VdaCommand& c : vda_commands_) take_vda(c, out);
  vda_commands_.clear();
}

void RobotLinks::reject(std::string_view robot_id, const std::string& reason, const std::string& detail) {
  bump(waypoints_rejected_);
  warnings_.warn(reason, "waypoint for '{}' ignored: {}: {}", protocol::escape_for_log(robot_id), reason,
                 detail);
}

void RobotLinks::on_message(std::string_view topic, std::span<const uint8_t> payload) {
  if (topic.starts_with(vda_tree_.interface_name + "/")) {
    on_vda_message(topic, payload);
    return;
  }
  protocol::ParsedCommandTopic parsed;
  if (auto s = protocol::parse_command_topic(topic, parsed); !s) {
    reject("?", std::string(protocol::reason_name(s.reason())), s.detail());
    return;
  }
  WaypointOrder order{std::string(parsed.robot_id), std::nullopt};
  protocol::CodecStatus s;
  switch (parsed.kind) {
    case protocol::CommandKind::V1Waypoint: {
      protocol::Point p;
      s = protocol::decode_v1_waypoint(payload, settings_.limits, p);
      if (s) order.target = Vec2{p.x, p.y};
      break;
    }
    case protocol::CommandKind::V2Waypoint: {
      protocol::V2Waypoint w;
      s = protocol::decode_v2_waypoint(payload, settings_.limits, w);
      if (s) order.target = Vec2{w.waypoint.x, w.waypoint.y};
      break;
    }
    case protocol::CommandKind::V2Path: {
      protocol::V2Path path;
      s = protocol::decode_v2_path(payload, settings_.limits, path);
      if (s && !path.points.empty()) order.target = Vec2{path.points.front().x, path.points.front().y};
      break;
    }
  }
  if (!s) {
    reject(order.robot_id, std::string(protocol::reason_name(s.reason())), s.detail());
    return;
  }
  bump(waypoints_received_);
  std::lock_guard lock(intake_mutex_);
  if (intake_.size() >= kMaxPendingOrders) {
    bump(orders_dropped_);
    return;
  }
  intake_.push_back(std::move(order));
}

}  // namespace slam::sim
