#pragma once
// slam-bridge's configuration: where the WebSocket face listens, whether the ROS 2 face runs and how often
// each kind of channel may be sent, with defaults, CLI11/YAML binding and one validator.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

#include "common/core/result.hpp"
#include "common/core/service_options.hpp"

namespace slam::bridge {

// How often each channel may go out (seconds between two messages on it). A channel is sent only
// when something changed and a client subscribed to it.
struct ChannelPeriods {
  double map_full_s = 5.0;     // the whole grid (large: width x height cells)
  double map_updates_s = 0.5;  // the region of the tiles changed since the last map message
  double robots_s = 0.2;       // robot markers and map -> robot frames
  double paths_s = 1.0;        // paths and targets
  double points_s = 1.0;       // each robot's recent measurement points
  double health_s = 1.0;       // services heard in heartbeats
};

struct BridgeOptions {
  ServiceOptions service;
  std::string bind = "127.0.0.1:8765";  // ADDR:PORT of the Foxglove WebSocket server
  ChannelPeriods periods;
  uint32_t points_per_robot = 100;  // recent measurement points kept per robot
  double path_timeout_s = 5.0;      // a path service call unanswered this long fails
  // A client whose unsent data exceeds this many bytes misses data messages until it catches up.
  uint32_t client_backlog_bytes = 16u << 20;
  // The ROS 2 face (rt/map, rt/tf, rt/goal_pose, rt/initialpose); --no-ros turns it off.
  bool ros = true;
  // The robot RViz2's goals and initial poses are for; empty: the robot nearest to the pose.
  std::string ros_robot;
};

// An address and port parsed from "ADDR:PORT".
struct BindAddress {
  std::string host;
  uint16_t port = 0;
};

// "127.0.0.1:8765" -> {"127.0.0.1", 8765}; an error naming what is wrong otherwise.
Result<BindAddress> parse_bind(const std::string& text);

void add_bridge_options(CLI::App& app, BridgeOptions& options);

// Ok, or the first bad key with the reason.
Status validate(const BridgeOptions& options);

}  // namespace slam::bridge
