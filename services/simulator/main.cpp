// slam-simulator: options -> world -> service (Cyclone DDS + MQTT) -> run -> tear down; or, with
// --play, recorded logs played over MQTT (log_player.hpp).
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
  slam::install_shutdown_handlers();
  slam::Counters counters;  // the node's or the log player's
  if (options.play.enabled()) return slam::exit_code("slam-simulator", play_logs(options, counters));
  auto world = load_world(options.world);
  if (!world) return slam::exit_error("slam-simulator", "--world: " + world.message(), slam::kExitUsage);
  auto node = SimNode::create(options, std::move(*world), counters);
  if (!node) return slam::exit_error("slam-simulator", node.message());
  (*node)->run();
  return slam::kExitOk;
}
