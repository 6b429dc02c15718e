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
#include "protocol/vda5050_codec.hpp"

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
  // RobotState and RobotOdometry go out at most this often per robot (presence changes at once):
  // they are each robot's status record. The pose stream readers follow is the FleetDigest.
  double state_period_s = 1.0;
  // Observations leave in batches (one DDS sample each): a batch waits at most this long.
  double batch_ms = 10.0;
  std::size_t max_robots = 10'000;
  // VDA 5050 robots (docs/protocol.md, "VDA 5050"): the gateway is their fleet control on the tree
  // <vda_tree.interface_name>/<vda_tree.major_version>/..., for the robots in vda_robots
  // ("<manufacturer>/<serialNumber>") or, with none listed, for any robot publishing under it.
  bool vda5050 = true;
  protocol::VdaTree vda_tree;
  std::vector<std::string> vda_robots;
  // The fleet digests (FleetDigest, FleetPoints): every robot in one sample each period, with up
  // to digest_points_per_robot of each robot's latest hits per points sample. The digest is the
  // pose stream the planner, the viewer and the bridge follow.
  double digest_period_s = 0.1;
  double digest_points_period_s = 1.0;
  std::size_t digest_points_per_robot = 16;
  std::size_t traffic_queue = 1024;  // MqttTraffic records waiting for the worker
  double traffic_rate = 2000.0;      // MqttTraffic records per second at most
  // Several gateways share the robots: the filters are subscribed as $share/<share_group>/<filter>
  // (each robot message reaches one gateway) and each robot's waypoints are sent by its owner only,
  // chosen from the gateways heard within peer_timeout_s (common/core/ownership.hpp). share false
  // (--no-share): a lone gateway with plain subscriptions that owns every robot from its start.
  bool share = true;
  std::string share_group = "slam-gateways";
  double peer_timeout_s = 1.5;
};

// Gateway heartbeats go out this often: peer_timeout_s must span a few of them.
inline constexpr double kGatewayHeartbeatPeriodS = 0.5;

// The filters the MQTT connection subscribes: mqtt.subscriptions and the VDA 5050 robot topics,
// shared when `share` is on.
std::vector<std::string> subscribed_filters(const GatewayOptions& options);

// Adds the common flags and every gateway flag to `app`, bound to `options`.
void add_gateway_options(CLI::App& app, GatewayOptions& options);

// Ok, or the first bad key with the reason ("qos must be 0, 1 or 2, not 3").
Status validate(const GatewayOptions& options);

}  // namespace slam::gateway
