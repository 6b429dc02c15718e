// slam-bridge: the fleet for Foxglove and Lichtblick over the Foxglove WebSocket protocol, and for
// RViz2 and Nav2 over ROS 2's DDS topics.
// Only wiring: the common service skeleton around BridgeNode.
#include "bridge/core/bridge_options.hpp"
#include "bridge/dds/bridge_node.hpp"
#include "common/fastdds/run_service.hpp"

int main(int argc, char** argv) {
  using namespace slam::bridge;
  BridgeOptions options;
  if (auto code = slam::start_service(
          "bridge",
          "slam-bridge: the map, robots, paths, points, frames and service health for Foxglove (WebSocket, "
          "foxglove.websocket.v1) and ROS 2 (rt/map, rt/tf); goals, initial poses and path requests back",
          argc, argv, options, add_bridge_options))
    return *code;
  return slam::run_service<BridgeNode>("bridge", options);
}
