// slam-simulator: options -> world -> service (Cyclone DDS + MQTT) -> run -> tear down; or, with
// --play, recorded logs played over MQTT (log_player.hpp).
#include "common/core/counters.hpp"
#include "common/core/service_options.hpp"
#include "common/core/shutdown.hpp"
#include "simulator/core/sim_options.hpp"
#include "simulator/core/world_loader.hpp"
#include "simulator/dds/sim_node.hpp"
#include "simulator/mqtt/log_player.hpp"

int main(int argc, char** argv) {
  using namespace slam::sim;
  SimOptions options;
  if (auto code =
          slam::start_service("simulator",
                              "slam-simulator: simulated robots in a hidden world, speaking the robot "
                              "protocol over MQTT and taking commands over DDS",
                              argc, argv, options, add_sim_options))
    return *code;
  if (options.play.enabled()) {
    slam::install_shutdown_handlers();
    slam::Counters counters;
    if (auto s = play_logs(options, counters); !s) {
      slam::report_error("slam-simulator", s.message());
      return slam::kExitFailure;
    }
    return slam::kExitOk;
  }
  auto world = load_world(options.world);
  if (!world) {
    slam::report_error("slam-simulator", "--world: " + world.message());
    return slam::kExitUsage;
  }
  slam::install_shutdown_handlers();

  slam::Counters counters;
  auto node = SimNode::create(options, std::move(*world), counters);
  if (!node) {
    slam::report_error("slam-simulator", node.message());
    return slam::kExitFailure;
  }
  (*node)->run();
  return slam::kExitOk;
}
