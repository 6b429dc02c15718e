// slam-gateway: translates robots' MQTT traffic (v1 binary, v2 JSON) to DDS and waypoint commands
// back. Only wiring: the common service skeleton around GatewayNode.
#include "common/fastdds/run_service.hpp"
#include "gateway/core/gateway_options.hpp"
#include "gateway/dds/gateway_node.hpp"

int main(int argc, char** argv) {
  using namespace slam::gateway;
  GatewayOptions options;
  if (auto code = slam::start_service(
          "gateway",
          "slam-gateway: robots' MQTT (v1/v2) <-> DDS observations, robot states and waypoint commands", argc,
          argv, options, add_gateway_options))
    return *code;
  return slam::run_service<GatewayNode>("gateway", options);
}
