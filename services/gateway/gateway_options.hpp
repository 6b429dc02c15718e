#pragma once
// slam-gateway's configuration: the MQTT connection, the codec limits, robot presence and the
// traffic log, with defaults, CLI11/YAML binding and one validator naming the bad key.
// `--broker URL` on the command line is `broker: URL` in a --config file.
#include <CLI/CLI.hpp>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "common/core/result.hpp"
#include "common/core/service_options.hpp"
#include "protocol/codec_types.hpp"

namespace slam::gateway {

struct MqttOptions {
  std::string broker = "tcp://127.0.0.1:1883";  // tcp://, mqtt://, ssl:// or mqtts://
  std::string client_id;                        // empty: slam-gateway-<host>-<pid>
  int qos = 1;                                  // subscriptions and commands
  bool persistent_session = false;              // false: clean session, re-subscribe on reconnect
  std::string username;
  std::string password;
  std::string tls_ca_file;    // PEM trust store; TLS when the broker URL is ssl:// or mqtts://
  std::string tls_cert_file;  // PEM client certificate chain (mutual TLS)
  std::string tls_key_file;   // PEM private key when not inside tls_cert_file
  int keepalive_s = 20;
  int connect_timeout_s = 5;
  double reconnect_min_s = 0.25;
  double reconnect_max_s = 30.0;
  std::vector<std::string> subscriptions{"v1/robot/+/adv", "v2/robot/+/+"};
};

struct GatewayOptions {
  ServiceOptions service;
  MqttOptions mqtt;
  protocol::CodecLimits limits;
  double offline_after_s = 5.0;  // silence that turns a robot offline
  double state_period_s = 0.1;   // RobotState is published at most this often per robot
  std::size_t max_robots = 10'000;
  std::size_t traffic_queue = 1024;  // MqttTraffic records waiting for the worker
  double traffic_rate = 2000.0;      // MqttTraffic records per second at most
};

// Adds the common flags and every gateway flag to `app`, bound to `options`.
void add_gateway_options(CLI::App& app, GatewayOptions& options);

// Ok, or the first bad key with the reason ("qos must be 0, 1 or 2, not 3").
Status validate(const GatewayOptions& options);

// True for ssl:// and mqtts:// broker URLs.
bool uses_tls(const std::string& broker);

}  // namespace slam::gateway
