// slam-simulator: options -> world -> service (Cyclone DDS + MQTT) -> run -> tear down.
#include <iostream>

#include "common/core/counters.hpp"
#include "common/core/service_options.hpp"
#include "common/core/shutdown.hpp"
#include "simulator/sim_node.hpp"
#include "simulator/sim_options.hpp"
#include "simulator/world_loader.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "slam-simulator: simulated robots in a hidden world, speaking the robot protocol over MQTT "
      "and taking commands over DDS"};
  slam::sim::SimOptions options;
  slam::sim::add_sim_options(app, options);
  if (auto code = slam::parse_command_line(app, argc, argv)) return *code;
  if (auto s = slam::sim::validate(options); !s) {
    std::cerr << "slam-simulator: error: " << s.message() << " (see --help)\n";
    return 2;
  }
  auto world = slam::sim::load_world(options.world);
  if (!world) {
    std::cerr << "slam-simulator: error: --world: " << world.message() << "\n";
    return 2;
  }
  if (!slam::start_logging("simulator", options.service)) return 2;
  slam::install_shutdown_handlers();

  slam::Counters counters;
  auto node = slam::sim::SimNode::create(options, std::move(*world), counters);
  if (!node) {
    spdlog::error("start-up failed: {}", node.message());
    return 1;
  }
  (*node)->run();
  return 0;
}
