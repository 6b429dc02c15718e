// CLI11 binding and validation of BridgeOptions.
#include "bridge/core/bridge_options.hpp"

#include <charconv>

namespace slam::bridge {

Result<BindAddress> parse_bind(const std::string& text) {
  const auto colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0) return Error{"bind must be ADDR:PORT, got '" + text + "'"};
  BindAddress out;
  out.host = text.substr(0, colon);
  const std::string port = text.substr(colon + 1);
  unsigned value = 0;
  const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), value);
  if (ec != std::errc{} || end != port.data() + port.size() || value == 0 || value > 65535)
    return Error{"bind port must be 1..65535, got '" + port + "'"};
  out.port = static_cast<uint16_t>(value);
  return out;
}

void add_bridge_options(CLI::App& app, BridgeOptions& o) {
  add_service_options(app, o.service);
  app.add_option("--bind", o.bind, "ADDR:PORT of the Foxglove WebSocket server (0.0.0.0 for every interface)")
      ->capture_default_str();
  app.add_option("--periods-map-full-s", o.periods.map_full_s,
                 "the whole grid goes out at most this often (s)")
      ->capture_default_str();
  app.add_option("--periods-map-updates-s", o.periods.map_updates_s,
                 "the changed part of the grid goes out at most this often (s)")
      ->capture_default_str();
  app.add_option("--periods-robots-s", o.periods.robots_s, "robot markers and frames at most this often (s)")
      ->capture_default_str();
  app.add_option("--periods-paths-s", o.periods.paths_s, "paths and targets at most this often (s)")
      ->capture_default_str();
  app.add_option("--periods-points-s", o.periods.points_s, "measurement points at most this often (s)")
      ->capture_default_str();
  app.add_option("--periods-health-s", o.periods.health_s, "service health at most this often (s)")
      ->capture_default_str();
  app.add_option("--points-per-robot", o.points_per_robot, "recent measurement points kept per robot")
      ->capture_default_str();
  app.add_option("--path-timeout-s", o.path_timeout_s, "a path service call unanswered this long fails (s)")
      ->capture_default_str();
  app.add_option("--client-backlog-bytes", o.client_backlog_bytes,
                 "a client with more unsent bytes than this misses data messages until it catches up")
      ->capture_default_str();
  app.add_flag("!--no-ros", o.ros, "no ROS 2 face (rt/map, rt/tf, rt/goal_pose, rt/initialpose)");
  app.add_option(
      "--ros-robot", o.ros_robot,
      "the robot RViz2's goals and initial poses are for (default: the robot nearest to the pose)");
}

Status validate(const BridgeOptions& o) {
  if (auto bind = parse_bind(o.bind); !bind) return bind.error();
  const std::pair<const char*, double> periods[] = {
      {"periods-map-full-s", o.periods.map_full_s}, {"periods-map-updates-s", o.periods.map_updates_s},
      {"periods-robots-s", o.periods.robots_s},     {"periods-paths-s", o.periods.paths_s},
      {"periods-points-s", o.periods.points_s},     {"periods-health-s", o.periods.health_s}};
  for (const auto& [key, value] : periods)
    if (Status s = check_seconds(key, value, 0.01, 3600.0); !s) return s;
  if (Status s = check_seconds("path-timeout-s", o.path_timeout_s, 0.1, 600.0); !s) return s;
  if (o.points_per_robot > 100000) return Error{"points-per-robot must be at most 100000"};
  if (o.ros_robot.size() > 64) return Error{"ros-robot must be at most 64 characters"};
  if (o.client_backlog_bytes < 65536) return Error{"client-backlog-bytes must be at least 65536"};
  return {};
}

}  // namespace slam::bridge
