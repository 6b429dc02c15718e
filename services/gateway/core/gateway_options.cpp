// CLI11 binding and validation of GatewayOptions.
#include "gateway/core/gateway_options.hpp"

#include <cmath>

#include "common/core/service_options.hpp"
#include "gateway/core/topic_filter.hpp"

namespace slam::gateway {

void add_gateway_options(CLI::App& app, GatewayOptions& o) {
  add_service_options(app, o.service);

  MqttOptions& m = o.mqtt;
  app.add_option("--broker", m.broker, "MQTT broker URL: tcp://, mqtt://, ssl:// or mqtts://host:port")
      ->capture_default_str();
  app.add_option("--client-id", m.client_id, "MQTT client id (default slam-gateway-<host>-<pid>)");
  app.add_option("--qos", m.qos, "MQTT QoS of subscriptions and commands (0, 1, 2)")->capture_default_str();
  app.add_flag("--persistent-session", m.persistent_session,
               "keep the MQTT session across reconnects (needs a fixed --client-id)");
  app.add_option("--username", m.username, "MQTT user name");
  app.add_option("--password", m.password,
                 "MQTT password (prefer a --config file readable only by the service)");
  app.add_option("--tls-ca-file", m.tls_ca_file, "PEM CA certificates trusted for the broker (ssl:// URLs)");
  app.add_option("--tls-cert-file", m.tls_cert_file, "PEM client certificate chain for mutual TLS");
  app.add_option("--tls-key-file", m.tls_key_file, "PEM client private key, when not in --tls-cert-file");
  app.add_option("--keepalive-s", m.keepalive_s, "MQTT keep-alive interval (s)")->capture_default_str();
  app.add_option("--connect-timeout-s", m.connect_timeout_s, "give up one connection attempt after (s)")
      ->capture_default_str();
  app.add_option("--reconnect-min-s", m.reconnect_min_s,
                 "first delay before reconnecting (s); doubles per failure")
      ->capture_default_str();
  app.add_option("--reconnect-max-s", m.reconnect_max_s, "longest delay between reconnection attempts (s)")
      ->capture_default_str();
  app.add_option("--subscribe", m.subscriptions, "MQTT filters to subscribe (repeatable)")
      ->capture_default_str();

  protocol::CodecLimits& l = o.limits;
  app.add_option("--units-per-meter", l.units_per_meter, "v1 robot units per metre")->capture_default_str();
  app.add_option("--max-points", l.max_points, "points or beams per message")->capture_default_str();
  app.add_option("--max-payload-bytes", l.max_payload_bytes, "largest accepted payload")
      ->capture_default_str();
  app.add_option("--max-abs-coordinate-m", l.max_abs_coordinate_m, "largest |x| or |y| accepted (m)")
      ->capture_default_str();
  app.add_option("--max-abs-angle-rad", l.max_abs_angle_rad, "largest |angle| accepted (rad)")
      ->capture_default_str();
  app.add_option("--scan-free-range-m", l.scan_free_range_m,
                 "a scan's beam without a return clears free space this far at most (m)")
      ->capture_default_str();

  app.add_option("--vda5050", o.vda5050, "serve VDA 5050 robots as their fleet control (on|off)")
      ->capture_default_str();
  app.add_option("--vda-interface", o.vda_tree.interface_name, "VDA 5050 interface name (first topic level)")
      ->capture_default_str();
  app.add_option("--vda-major-version", o.vda_tree.major_version,
                 "VDA 5050 major version (second topic level): v2 speaks 2.x")
      ->capture_default_str();
  app.add_option(
      "--vda-robot", o.vda_robots,
      "a VDA 5050 robot as <manufacturer>/<serialNumber> (repeatable); none: any robot under the tree");

  app.add_option("--offline-after-s", o.offline_after_s, "a robot silent this long (s) is offline")
      ->capture_default_str();
  app.add_option("--state-period-s", o.state_period_s,
                 "RobotState and RobotOdometry published at most this often per robot (s); "
                 "presence changes go out at once, poses at the digest period")
      ->capture_default_str();
  app.add_option("--batch-ms", o.batch_ms,
                 "an observation waits at most this long (ms) for others to share its DDS sample")
      ->capture_default_str();
  app.add_option("--max-robots", o.max_robots,
                 "robots tracked at most; messages from further ones are refused")
      ->capture_default_str();
  app.add_option("--digest-period-s", o.digest_period_s,
                 "every robot's map pose and presence published in one FleetDigest this often (s): "
                 "the pose stream the planner and the viewer follow")
      ->capture_default_str();
  app.add_option("--digest-points-period-s", o.digest_points_period_s,
                 "the robots' latest obstacle points published in one FleetPoints this often (s)")
      ->capture_default_str();
  app.add_option("--digest-points-per-robot", o.digest_points_per_robot,
                 "latest obstacle points of each robot in one FleetPoints at most")
      ->capture_default_str();
  app.add_option("--traffic-queue", o.traffic_queue, "MQTT traffic records queued for the viewer")
      ->capture_default_str();
  app.add_option("--traffic-rate", o.traffic_rate, "MQTT traffic records per second published at most")
      ->capture_default_str();

  app.add_option("--share-group", o.share_group,
                 "MQTT shared-subscription group of the gateways that share the robots")
      ->capture_default_str();
  app.add_flag("--no-share{false}", o.share,
               "a lone gateway: plain subscriptions, sends every robot's waypoints from the start");
  app.add_option("--peer-timeout-s", o.peer_timeout_s,
                 "a gateway unheard this long (s) is gone and its robots move to the others")
      ->capture_default_str();
}

std::vector<std::string> subscribed_filters(const GatewayOptions& o) {
  std::vector<std::string> filters = o.mqtt.subscriptions;
  if (o.vda5050) {
    for (std::string& f : protocol::vda_robot_filters(o.vda_tree)) filters.push_back(std::move(f));
  }
  if (!o.share) return filters;
  std::vector<std::string> shared;
  for (const std::string& f : filters) shared.push_back(mqtt::shared_filter(o.share_group, f));
  return shared;
}

namespace {

// A topic level the gateway builds topics from: not empty, no '/', '+', '#' and clean text.
Status check_level(std::string_view key, std::string_view level) {
  if (level.empty() || level.find_first_of("/+#") != std::string_view::npos)
    return Error{std::string(key) + " '" + std::string(level) +
                 "' must be one topic level without '/', '+' or '#'"};
  return validate_topic_name(level);
}

Status validate_vda(const GatewayOptions& o) {
  if (auto s = check_level("vda-interface", o.vda_tree.interface_name); !s) return s;
  const std::string& major = o.vda_tree.major_version;
  if (major.size() < 2 || major[0] != 'v' || major.find_first_not_of("0123456789", 1) != std::string::npos)
    return Error{"vda-major-version '" + major + "' must be 'v' and a number, e.g. v2"};
  for (const std::string& robot : o.vda_robots) {
    const auto slash = robot.find('/');
    if (slash == std::string::npos)
      return Error{"vda-robot '" + robot + "' must be <manufacturer>/<serialNumber>"};
    if (auto s = check_level("vda-robot manufacturer", robot.substr(0, slash)); !s) return s;
    if (auto s = check_level("vda-robot serialNumber", robot.substr(slash + 1)); !s) return s;
  }
  return Status::ok();
}

}  // namespace

Status validate(const GatewayOptions& o) {
  const MqttOptions& m = o.mqtt;
  if (auto s = mqtt::validate(m); !s) return s;
  for (const std::string& filter : m.subscriptions) {
    if (auto s = validate_filter(filter); !s) return Error{"subscribe: " + s.message()};
  }

  if (auto s = protocol::validate(o.limits); !s) return s;
  if (auto s = validate_vda(o); !s) return s;
  if (auto s = check_seconds("offline-after-s", o.offline_after_s, 0.1, 86400.0); !s) return s;
  if (auto s = check_seconds("state-period-s", o.state_period_s, 0.01, 10.0); !s) return s;
  if (!std::isfinite(o.batch_ms) || o.batch_ms < 0.0 || o.batch_ms > 1000.0)
    return Error{"batch-ms must be between 0 and 1000"};
  if (o.max_robots == 0) return Error{"max-robots must be at least 1"};
  if (auto s = check_seconds("digest-period-s", o.digest_period_s, 0.01, 60.0); !s) return s;
  if (auto s = check_seconds("digest-points-period-s", o.digest_points_period_s, 0.01, 60.0); !s) return s;
  if (o.digest_points_per_robot > 10'000) return Error{"digest-points-per-robot must be 10000 at most"};
  if (o.traffic_queue == 0 || o.traffic_queue > 1'000'000)
    return Error{"traffic-queue must be between 1 and 1000000"};
  if (!std::isfinite(o.traffic_rate) || o.traffic_rate < 0.0) return Error{"traffic-rate must be 0 or more"};
  if (o.share) {
    if (auto s = mqtt::validate_share_group(o.share_group); !s) return s;
    for (const std::string& filter : subscribed_filters(o)) {
      if (auto s = validate_filter(filter); !s) return Error{"share-group: " + s.message()};
    }
  }
  // Several heartbeats long, or one late heartbeat would hand a live gateway's robots to another.
  if (auto s = check_seconds("peer-timeout-s", o.peer_timeout_s, 2.0 * kGatewayHeartbeatPeriodS, 60.0); !s)
    return s;
  return Status::ok();
}

}  // namespace slam::gateway
