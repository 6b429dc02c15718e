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
#include "common/mqtt/mqtt_options.hpp"
#include "protocol/codec_types.hpp"

namespace slam::gateway {

// The MQTT connection's settings; client_id empty: slam-gateway-<host>-<pid>.
using MqttOptions = mqtt::ConnectionOptions;

// The common connection defaults plus the robot topics the gateway listens to.
inline MqttOptions default_mqtt_options() {
  MqttOptions m;
  m.subscriptions = {"v1/robot/+/adv", "v2/robot/+/+"};
  return m;
}

struct GatewayOptions {
  ServiceOptions service;
  MqttOptions mqtt = default_mqtt_options();
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

}  // namespace slam::gateway
