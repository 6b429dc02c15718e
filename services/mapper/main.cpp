// slam-mapper: owns the occupancy grid and every stored observation; publishes snapshots and patches.
// Only wiring: options -> (offline command) -> logging -> node (configure) -> heartbeat -> loop -> tear down.
#include <iostream>

#include "common/core/shutdown.hpp"
#include "common/fastdds/heartbeat.hpp"
#include "mapper/mapper_node.hpp"
#include "mapper/mapper_offline.hpp"
#include "mapper/mapper_options.hpp"

int main(int argc, char** argv) {
  CLI::App app{"slam-mapper: builds the occupancy grid from robot observations, stores them, serves the map"};
  slam::mapper::MapperOptions options;
  slam::mapper::add_mapper_options(app, options);
  if (auto code = slam::parse_command_line(app, argc, argv)) return *code;
  if (auto s = slam::mapper::validate(options); !s) {
    std::cerr << "slam-mapper: error: " << s.message() << "\n";
    return 2;
  }
  if (!slam::start_logging("mapper", options.service)) return 2;

  if (options.offline()) {
    auto done = slam::mapper::run_offline(options);
    if (!done) {
      std::cerr << "slam-mapper: error: " << done.message() << "\n";
      return 1;
    }
    std::cout << *done << "\n";
    return 0;
  }

  slam::install_shutdown_handlers();
  slam::Counters counters;
  auto node = slam::mapper::MapperNode::create(options, counters);
  if (!node) {
    std::cerr << "slam-mapper: error: " << node.message() << "\n";
    return 1;
  }
  auto heartbeat = slam::HeartbeatPublisher::start((*node)->participant(), "mapper", counters);
  if (!heartbeat) {
    std::cerr << "slam-mapper: error: heartbeat: " << heartbeat.message() << "\n";
    return 1;
  }
  (*heartbeat)->set_state(slam::SERVICE_RUNNING);

  while (!slam::shutdown_requested()) (*node)->run_once();

  spdlog::info("mapper stopping");
  (*heartbeat)->set_state(slam::SERVICE_STOPPING);
  heartbeat->reset();
  node->reset();
  return 0;
}
