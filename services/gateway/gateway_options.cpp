// CLI11 binding and validation of GatewayOptions.
#include "gateway/gateway_options.hpp"

#include <cmath>
#include <fstream>

#include "gateway/topic_filter.hpp"

namespace slam::gateway {

namespace {

bool starts_with(const std::string& s, const char* prefix) {
  return s.rfind(prefix, 0) == 0;
}

Status readable(const char* key, const std::string& path) {
  if (path.empty()) return Status::ok();
  std::ifstream f(path);
  if (!f) return Error{std::string(key) + ": cannot read '" + path + "'"};
  return Status::ok();
}

Status seconds(const char* key, double value, double min, double max) {
  if (!std::isfinite(value) || value < min || value > max) {
    return Error{std::string(key) + " must be between " + std::to_string(min) + " and " +
                 std::to_string(max) + " seconds"};
  }
  return Status::ok();
}

}  // namespace

bool uses_tls(const std::string& broker) {
  return starts_with(broker, "ssl://") || starts_with(broker, "mqtts://");
}

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

  app.add_option("--offline-after-s", o.offline_after_s, "a robot silent this long (s) is offline")
      ->capture_default_str();
  app.add_option("--state-period-s", o.state_period_s,
                 "RobotState published at most this often per robot (s)")
      ->capture_default_str();
  app.add_option("--max-robots", o.max_robots,
                 "robots tracked at most; messages from further ones are refused")
      ->capture_default_str();
  app.add_option("--traffic-queue", o.traffic_queue, "MQTT traffic records queued for the viewer")
      ->capture_default_str();
  app.add_option("--traffic-rate", o.traffic_rate, "MQTT traffic records per second published at most")
      ->capture_default_str();
}

Status validate(const GatewayOptions& o) {
  const MqttOptions& m = o.mqtt;
  const bool tls = uses_tls(m.broker);
  const bool known_scheme = tls || starts_with(m.broker, "tcp://") || starts_with(m.broker, "mqtt://");
  if (!known_scheme || m.broker.find("://") + 3 >= m.broker.size()) {
    return Error{"broker '" + m.broker + "' must look like tcp://host:port, mqtt://, ssl:// or mqtts://"};
  }
  if (m.qos < 0 || m.qos > 2) return Error{"qos must be 0, 1 or 2, not " + std::to_string(m.qos)};
  if (m.persistent_session && m.client_id.empty()) {
    return Error{"persistent-session needs a fixed client-id (the broker keeps the session under that id)"};
  }
  if (m.client_id.size() > 65535) return Error{"client-id is longer than 65535 bytes"};
  if (!m.password.empty() && m.username.empty()) return Error{"password is set but username is not"};
  const bool tls_files = !m.tls_ca_file.empty() || !m.tls_cert_file.empty() || !m.tls_key_file.empty();
  if (tls_files && !tls)
    return Error{"tls-* files are set but broker '" + m.broker + "' is not ssl:// or mqtts://"};
  if (!m.tls_key_file.empty() && m.tls_cert_file.empty())
    return Error{"tls-key-file is set but tls-cert-file is not"};
  if (auto s = readable("tls-ca-file", m.tls_ca_file); !s) return s;
  if (auto s = readable("tls-cert-file", m.tls_cert_file); !s) return s;
  if (auto s = readable("tls-key-file", m.tls_key_file); !s) return s;
  if (m.keepalive_s < 1 || m.keepalive_s > 3600) return Error{"keepalive-s must be between 1 and 3600"};
  if (m.connect_timeout_s < 1 || m.connect_timeout_s > 300)
    return Error{"connect-timeout-s must be between 1 and 300"};
  if (auto s = seconds("reconnect-min-s", m.reconnect_min_s, 0.01, 60.0); !s) return s;
  if (auto s = seconds("reconnect-max-s", m.reconnect_max_s, m.reconnect_min_s, 3600.0); !s) return s;
  for (const std::string& filter : m.subscriptions) {
    if (auto s = validate_filter(filter); !s) return Error{"subscribe: " + s.message()};
  }

  if (auto s = protocol::validate(o.limits); !s) return s;
  if (auto s = seconds("offline-after-s", o.offline_after_s, 0.1, 86400.0); !s) return s;
  if (auto s = seconds("state-period-s", o.state_period_s, 0.01, 10.0); !s) return s;
  if (o.max_robots == 0) return Error{"max-robots must be at least 1"};
  if (o.traffic_queue == 0 || o.traffic_queue > 1'000'000)
    return Error{"traffic-queue must be between 1 and 1000000"};
  if (!std::isfinite(o.traffic_rate) || o.traffic_rate < 0.0) return Error{"traffic-rate must be 0 or more"};
  return Status::ok();
}

}  // namespace slam::gateway
