// slamctl: script the fleet without the GUI. Each subcommand talks DDS, prints what it got and exits
// non-zero with a one-line reason on failure or timeout.
#include <iostream>

#include "common/core/service_options.hpp"
#include "common/core/shutdown.hpp"
#include "slamctl/commands.hpp"
#include "slamctl/format.hpp"

namespace {

slam::Point2 point(double x, double y) {
  slam::Point2 p;
  p.x(x);
  p.y(y);
  return p;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"slamctl: inspect and command the SLAM fleet over DDS"};
  app.require_subcommand(1);
  slam::ServiceOptions options;
  options.log_level = "warn";
  slam::add_service_options(app, options);
  double timeout_s = 5.0;
  app.add_option("--timeout", timeout_s, "seconds to wait for services and replies")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();

  auto* status = app.add_subcommand("status", "services seen, with their heartbeats and counters");
  auto* robots = app.add_subcommand("robots", "known robots: id, pose, last seen, goal mode");

  std::string robot;
  std::string mode_name;
  std::vector<double> xy;
  double square_size = 1.0;
  bool centred = false;
  auto* goal = app.add_subcommand("goal", "set a robot's standing goal: goal ROBOT|all MODE [x y]");
  goal->add_option("robot", robot, "robot id, or 'all'")->required();
  goal->add_option("mode", mode_name, "idle, direct, planned, square, explore, home or stop")->required();
  goal->add_option("xy", xy, "target x y in metres (direct, planned, square)")->expected(0, 2);
  goal->add_option("--size", square_size, "square side in metres")->check(CLI::PositiveNumber);
  goal->add_flag("--centred", centred, "square centred on the target instead of starting at it");

  std::vector<double> ends;
  std::string algorithm = "astar";
  double budget = 1.0;
  auto* path = app.add_subcommand("path", "plan a path: path x0 y0 x1 y1");
  path->add_option("coordinates", ends, "start x y, goal x y (metres)")->expected(4)->required();
  path->add_option("--algorithm", algorithm, "astar, rrtconnect, rrtstar or prmstar")->capture_default_str();
  path->add_option("--budget", budget, "time budget in seconds")->capture_default_str();

  std::string map_file;
  auto* map =
      app.add_subcommand("map", "save or load the map (ROS map_server YAML + PGM, on the mapper's disk)");
  map->require_subcommand(1);
  auto* map_save = map->add_subcommand("save", "export the map to FILE.yaml");
  map_save->add_option("file", map_file, "YAML path")->required();
  auto* map_load = map->add_subcommand("load", "import FILE.yaml as a prior");
  map_load->add_option("file", map_file, "YAML path")->required();

  slam::GridConfig grid_config;
  double resolution = 0.05, width = 0, height = 0, inflation = -1;
  std::vector<double> origin;
  bool legacy = false;
  auto* grid = app.add_subcommand("grid", "change the grid layout (the mapper rebuilds from its store)");
  grid->add_option("--resolution", resolution, "metres per cell")->check(CLI::PositiveNumber)->required();
  grid->add_option("--width", width, "metres (0: keep growing as robots explore)");
  grid->add_option("--height", height, "metres");
  grid->add_option("--origin", origin, "x y of the lower-left corner")->expected(2);
  grid->add_option("--inflation", inflation, "robot radius in metres for the restricted layer");
  grid->add_flag("--legacy", legacy, "2019 behaviour: points obstruct their cell, nothing is cleared");

  std::vector<double> cell;
  auto* obstruct = app.add_subcommand("obstruct", "mark the cell at x y occupied by hand");
  obstruct->add_option("xy", cell, "x y in metres")->expected(2)->required();
  auto* unobstruct = app.add_subcommand("unobstruct", "remove a manual obstruction at x y");
  unobstruct->add_option("xy", cell, "x y in metres")->expected(2)->required();
  auto* reset = app.add_subcommand("reset", "delete every observation of a robot and rebuild the map");
  reset->add_option("robot", robot, "robot id")->required();

  uint32_t count = 1;
  auto* sim = app.add_subcommand("sim", "control the simulator");
  sim->require_subcommand(1);
  auto* sim_spawn = sim->add_subcommand("spawn", "add N robots at random free poses");
  sim_spawn->add_option("count", count, "how many")->required()->check(CLI::Range(1, 10000));
  auto* sim_remove = sim->add_subcommand("remove", "remove a robot");
  sim_remove->add_option("robot", robot, "robot id")->required();
  auto* sim_pause = sim->add_subcommand("pause", "freeze every simulated robot");
  auto* sim_resume = sim->add_subcommand("resume", "continue");

  std::string topic;
  int echo_count = 0;
  auto* echo = app.add_subcommand("echo", "print samples of a topic (see docs/topics.md) until Ctrl-C");
  echo->add_option("topic", topic, "topic name, e.g. slam/robot/state")->required();
  echo->add_option("-n,--count", echo_count, "stop after N samples");

  if (auto code = slam::parse_command_line(app, argc, argv)) return *code;
  if (!slam::start_logging("slamctl", options)) return 2;
  slam::install_shutdown_handlers();

  auto participant = slam::dds::Participant::create(options.domain, "slamctl");
  if (!participant) {
    std::cerr << "slamctl: " << participant.message() << "\n";
    return 1;
  }
  slam::ctl::Session session(std::move(*participant),
                             std::chrono::milliseconds(static_cast<int64_t>(timeout_s * 1000)));

  if (*status) return slam::ctl::cmd_status(session);
  if (*robots) return slam::ctl::cmd_robots(session);
  if (*goal) {
    const auto mode = slam::ctl::parse_goal_mode(mode_name);
    if (!mode) {
      std::cerr << "slamctl: unknown mode '" << mode_name
                << "' (idle, direct, planned, square, explore, home, stop)\n";
      return 2;
    }
    const bool needs_target =
        *mode == slam::GOAL_DIRECT || *mode == slam::GOAL_PLANNED || *mode == slam::GOAL_SQUARE;
    if (needs_target && xy.size() != 2) {
      std::cerr << "slamctl: mode " << mode_name << " needs a target: goal " << robot << " " << mode_name
                << " X Y\n";
      return 2;
    }
    return slam::ctl::cmd_goal(session, robot, *mode, xy.size() == 2 ? point(xy[0], xy[1]) : point(0, 0),
                               square_size, centred);
  }
  if (*path)
    return slam::ctl::cmd_path(session, point(ends[0], ends[1]), point(ends[2], ends[3]), algorithm, budget);
  if (*map_save) return slam::ctl::cmd_map_file(session, slam::MAP_EXPORT, map_file);
  if (*map_load) return slam::ctl::cmd_map_file(session, slam::MAP_IMPORT, map_file);
  if (*grid) {
    grid_config.resolution(resolution);
    grid_config.width_m(width);
    grid_config.height_m(height);
    grid_config.origin(origin.size() == 2 ? point(origin[0], origin[1]) : point(0, 0));
    grid_config.inflation_radius(inflation);
    grid_config.legacy_mode(legacy);
    return slam::ctl::cmd_grid(session, grid_config);
  }
  if (*obstruct) return slam::ctl::cmd_map_edit(session, slam::EDIT_OBSTRUCT, point(cell[0], cell[1]), "");
  if (*unobstruct)
    return slam::ctl::cmd_map_edit(session, slam::EDIT_UNOBSTRUCT, point(cell[0], cell[1]), "");
  if (*reset) return slam::ctl::cmd_map_edit(session, slam::EDIT_RESET_ROBOT, point(0, 0), robot);
  if (*sim_spawn) return slam::ctl::cmd_sim(session, slam::SIM_SPAWN, count, "");
  if (*sim_remove) return slam::ctl::cmd_sim(session, slam::SIM_REMOVE, 0, robot);
  if (*sim_pause) return slam::ctl::cmd_sim(session, slam::SIM_PAUSE, 0, "");
  if (*sim_resume) return slam::ctl::cmd_sim(session, slam::SIM_RESUME, 0, "");
  if (*echo) return slam::ctl::cmd_echo(session, topic, echo_count);
  return 2;
}
