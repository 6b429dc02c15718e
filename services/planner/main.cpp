// slam-planner: path requests, per-robot goals, waypoint streams and exploration over DDS.
// Only wiring: options -> logging -> node (configure) -> heartbeat -> loop -> tear down in reverse.
#include <iostream>

#include "common/core/shutdown.hpp"
#include "common/fastdds/heartbeat.hpp"
#include "planner/planner_node.hpp"
#include "planner/planner_options.hpp"

int main(int argc, char** argv) {
  CLI::App app{"slam-planner: answers path requests, drives each robot's standing goal, explores"};
  slam::planner::PlannerOptions options;
  slam::planner::add_planner_options(app, options);
  if (auto code = slam::parse_command_line(app, argc, argv)) return *code;
  if (auto s = slam::planner::validate(options); !s) {
    std::cerr << "slam-planner: error: " << s.message() << "\n";
    return 2;
  }
  if (!slam::start_logging("planner", options.service)) return 2;
  slam::install_shutdown_handlers();

  slam::Counters counters;
  auto node = slam::planner::PlannerNode::create(options, counters);
  if (!node) {
    std::cerr << "slam-planner: error: " << node.message() << "\n";
    return 1;
  }
  auto heartbeat = slam::HeartbeatPublisher::start((*node)->participant(), "planner", counters);
  if (!heartbeat) {
    std::cerr << "slam-planner: error: heartbeat: " << heartbeat.message() << "\n";
    return 1;
  }
  (*heartbeat)->set_state(slam::SERVICE_RUNNING);

  while (!slam::shutdown_requested()) (*node)->run_once();

  spdlog::info("planner stopping");
  (*heartbeat)->set_state(slam::SERVICE_STOPPING);
  heartbeat->reset();
  node->reset();
  return 0;
}
