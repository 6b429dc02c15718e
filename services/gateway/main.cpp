// slam-gateway: translates robots' MQTT traffic (v1 binary, v2 JSON) to DDS and waypoint commands
// back. Only wiring: options -> logging -> node (configure) -> heartbeat -> loop -> tear down.
#include <iostream>

#include "common/core/shutdown.hpp"
#include "common/fastdds/heartbeat.hpp"
#include "gateway/gateway_node.hpp"
#include "gateway/gateway_options.hpp"

int main(int argc, char** argv) {
  CLI::App app{"slam-gateway: robots' MQTT (v1/v2) <-> DDS observations, robot states and waypoint commands"};
  slam::gateway::GatewayOptions options;
  slam::gateway::add_gateway_options(app, options);
  if (auto code = slam::parse_command_line(app, argc, argv)) return *code;
  if (auto s = slam::gateway::validate(options); !s) {
    std::cerr << "slam-gateway: error: " << s.message() << "\n";
    return 2;
  }
  if (!slam::start_logging("gateway", options.service)) return 2;
  slam::install_shutdown_handlers();

  slam::Counters counters;
  auto node = slam::gateway::GatewayNode::create(options, counters);
  if (!node) {
    std::cerr << "slam-gateway: error: " << node.message() << "\n";
    return 1;
  }
  auto heartbeat = slam::HeartbeatPublisher::start((*node)->participant(), "gateway", counters);
  if (!heartbeat) {
    std::cerr << "slam-gateway: error: heartbeat: " << heartbeat.message() << "\n";
    return 1;
  }
  (*heartbeat)->set_state(slam::SERVICE_RUNNING);

  while (!slam::shutdown_requested()) (*node)->run_once();

  spdlog::info("gateway stopping");
  (*heartbeat)->set_state(slam::SERVICE_STOPPING);
  heartbeat->reset();
  node->reset();
  return 0;
}
