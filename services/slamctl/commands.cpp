#include "slamctl/commands.hpp"

#include <atomic>

#include "slamctl/fleet_commands.hpp"
#include "slamctl/map_commands.hpp"
#include "slamctl/record.hpp"
#include "slamctl/session_io.hpp"
#include "slamctl/store_commands.hpp"

namespace slam::ctl {
namespace {

template <class T, class P>
int echo(Session& s, const dds::Topic<T, P>& topic, int count) {
  std::atomic<int> seen{0};
  auto reader = dds::make_reader(s.participant(), topic, [&](const T& sample, const auto&) {
    if (count > 0 && seen >= count) return;
    std::printf("%s\n", describe(sample).c_str());
    std::fflush(stdout);
    ++seen;
  });
  if (!reader) return fail(reader.message());
  while (!shutdown_requested() && (count <= 0 || seen < count)) std::this_thread::sleep_for(20ms);
  return 0;
}

}  // namespace

uint64_t Session::next_goal_id() {
  return goal_ids_.next();
}

namespace {

// Each subcommand: its handler, then `add_*`, which adds its arguments to its CLI11 subcommand and
// returns the handler bound to them; the table at the end names them in --help order.

int cmd_sim(Session& s, SimCommandKind kind, uint32_t count, const std::string& robot) {
  SimControl c;
  c.kind(kind);
  c.count(count);
  c.robot_id(robot);
  c.speed_factor(1.0);
  const auto reply = request(s, dds::kSimControl, c, dds::kSimReply, "simulator");
  if (!reply) return kExitFailure;
  if (!reply->ok()) return fail(reply->message().to_string());
  std::string done;
  switch (kind) {
    case SIM_SPAWN:
      done = "spawned " + std::to_string(count) + " simulated robot(s)";
      break;
    case SIM_REMOVE:
      done = "removed simulated robot " + robot;
      break;
    case SIM_PAUSE:
      done = "simulation paused";
      break;
    case SIM_RESUME:
      done = "simulation resumed";
      break;
    default:
      done = "simulator command done";
      break;
  }
  if (reply->message().size() > 0) done += ": " + reply->message().to_string();
  std::printf("%s\n", done.c_str());
  return 0;
}

struct SimArgs {
  uint32_t count = 1;
  std::string robot;
};

Handler add_sim(CLI::App& cli) {
  auto a = std::make_shared<SimArgs>();
  cli.require_subcommand(1);
  auto* spawn = cli.add_subcommand("spawn", "add N robots at random free poses");
  spawn->add_option("count", a->count, "how many")->required()->check(CLI::Range(1, 10000));
  auto* remove = cli.add_subcommand("remove", "remove a robot");
  remove->add_option("robot", a->robot, "robot id")->required();
  auto* pause = cli.add_subcommand("pause", "freeze every simulated robot");
  cli.add_subcommand("resume", "continue");
  return [a, spawn, remove, pause](Session& s) {
    if (spawn->parsed()) return cmd_sim(s, SIM_SPAWN, a->count, "");
    if (remove->parsed()) return cmd_sim(s, SIM_REMOVE, 0, a->robot);
    return cmd_sim(s, pause->parsed() ? SIM_PAUSE : SIM_RESUME, 0, "");
  };
}

int cmd_echo(Session& s, const std::string& topic, int count) {
  if (topic == topics::kRobotObservations.name) return echo(s, dds::kRobotObservations, count);
  if (topic == topics::kRobotState.name) return echo(s, dds::kRobotState, count);
  if (topic == topics::kRobotOdometry.name) return echo(s, dds::kRobotOdometry, count);
  if (topic == topics::kPoseCorrection.name) return echo(s, dds::kPoseCorrection, count);
  if (topic == topics::kInitialPose.name) return echo(s, dds::kInitialPose, count);
  if (topic == topics::kGridSnapshot.name) return echo(s, dds::kGridSnapshot, count);
  if (topic == topics::kGridTiles.name) return echo(s, dds::kGridTiles, count);
  if (topic == topics::kRobotPath.name) return echo(s, dds::kRobotPath, count);
  if (topic == topics::kWaypointCommand.name) return echo(s, dds::kWaypointCommand, count);
  if (topic == topics::kNavGoal.name) return echo(s, dds::kNavGoal, count);
  if (topic == topics::kMqttTraffic.name) return echo(s, dds::kMqttTraffic, count);
  if (topic == topics::kSimGroundTruth.name) return echo(s, dds::kSimGroundTruth, count);
  if (topic == topics::kHeartbeat.name) return echo(s, dds::kHeartbeat, count);
  if (topic == topics::kMapReply.name) return echo(s, dds::kMapReply, count);
  if (topic == topics::kPathReply.name) return echo(s, dds::kPathReply, count);
  if (topic == topics::kAlert.name) return echo(s, dds::kAlert, count);
  if (topic == topics::kForgetRobot.name) return echo(s, dds::kForgetRobot, count);
  if (topic == topics::kFleetDigest.name) return echo(s, dds::kFleetDigest, count);
  if (topic == topics::kFleetPoints.name) return echo(s, dds::kFleetPoints, count);
  return fail("cannot echo '" + topic + "': see docs/topics.md for topic names");
}

struct EchoArgs {
  std::string topic;
  int count = 0;
};

Handler add_echo(CLI::App& cli) {
  auto a = std::make_shared<EchoArgs>();
  cli.add_option("topic", a->topic, "topic name, e.g. slam/robot/state")->required();
  cli.add_option("-n,--count", a->count, "stop after N samples");
  return [a](Session& s) { return cmd_echo(s, a->topic, a->count); };
}

}  // namespace

Handlers add_subcommands(CLI::App& app) {
  app.require_subcommand(1);
  Handlers handlers;
  for (const Subcommand& sub : subcommands()) {
    CLI::App* cli = app.add_subcommand(std::string(sub.name), std::string(sub.help));
    handlers.emplace_back(cli, sub.add_options(*cli));
  }
  return handlers;
}

int run_parsed(const Handlers& handlers, Session& session) {
  for (const auto& [cli, run] : handlers)
    if (cli->parsed()) return run(session);
  return kExitUsage;
}

const std::vector<Subcommand>& subcommands() {
  static const std::vector<Subcommand> table{
      {"status", "one line per service: state, uptime, main rates, error counters", add_status},
      {"robots", "known robots: id, map-frame pose, last seen, goal mode, correction", add_robots},
      {"alerts", "active alerts: robots offline, low batteries, silent services", add_alerts},
      {"forget", "drop a robot from gateways, planners and viewers (its map data stays)", add_forget},
      {"goal", "set a robot's standing goal: goal ROBOT|all MODE [x y]", add_goal},
      {"mission",
       "send a robot waypoints to drive in order: mission ROBOT x1 y1 x2 y2 ... [--loop] | --file FILE",
       add_mission},
      {"missions", "each robot's mission: waypoint being driven to, laps done, status", add_missions},
      {"path", "plan a path: path x0 y0 x1 y1", add_path},
      {"map", "save or load the map (ROS map_server YAML + PGM, on the mapper's disk)", add_map},
      {"trajectory",
       "write a robot's corrected trajectory (TUM or CARMEN text, on the mapper's disk): trajectory ROBOT "
       "FILE",
       add_trajectory},
      {"grid", "change the grid layout (the mapper rebuilds from its store)", add_grid},
      {"obstruct", "mark the cell at x y occupied by hand", add_obstruct},
      {"unobstruct", "remove a manual obstruction at x y", add_unobstruct},
      {"reset", "delete every observation of a robot and rebuild the map", add_reset},
      {"store", "what the mapper's store keeps: store stats [--store FILE] (reads the file)", add_store},
      {"pose", "set a robot's pose in the map (initial pose): pose ROBOT X Y THETA_DEG", add_pose},
      {"placement", "accept or reject where the server placed a robot: placement accept|reject ROBOT",
       add_placement},
      {"sim", "control the simulator", add_sim},
      {"echo", "print samples of a topic (see docs/topics.md) until Ctrl-C", add_echo},
      {"record", "record every topic (or --topics) to an MCAP file Foxglove opens", add_record},
      {"replay", "publish a recorded MCAP file again, with its timing (--rate to scale)", add_replay},
  };
  return table;
}

}  // namespace slam::ctl
