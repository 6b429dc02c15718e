#include "slamctl/fleet_commands.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <numbers>

#include "common/core/clock.hpp"
#include "common/core/geometry.hpp"
#include "common/fastdds/fleet_messages.hpp"
#include "slamctl/mission_file.hpp"
#include "slamctl/session_io.hpp"

namespace slam::ctl {
namespace {

// --json on status, robots and alerts: the same facts as one JSON array, for scripts.
struct ListArgs {
  bool json = false;
  bool verbose = false;  // status: every counter
  bool all = false;      // alerts: cleared ones too
};

int cmd_status(Session& s, const ListArgs& a) {
  Latest<Heartbeat> beats(s, dds::kHeartbeat, [](const Heartbeat& h) {
    return h.service().to_string() + "/" + h.instance_id().to_string();
  });
  if (!beats.ok()) return 1;
  // Heartbeats come once a second: listen long enough for two of each, for the rates.
  listen_after_match(s, beats, std::min<std::chrono::milliseconds>(s.timeout(), 2500ms));
  const auto latest = beats.take();
  const auto first = beats.take_first();
  if (latest.empty()) return fail("no service seen on DDS domain " + std::to_string(s.domain()));
  std::vector<ServiceSeen> services;
  for (const auto& [key, hb] : latest)
    services.push_back(service_seen(msg::from_idl(first.at(key)), msg::from_idl(hb)));
  const int64_t now = now_ns();
  if (a.json) {
    std::printf("%s", services_json(services, now).c_str());
    return 0;
  }
  for (const ServiceSeen& seen : services) std::printf("%s", format_service(seen, now, a.verbose).c_str());
  return 0;
}

}  // namespace

Handler add_status(CLI::App& cli) {
  auto a = std::make_shared<ListArgs>();
  cli.add_flag("--json", a->json, "one JSON array: every service with its counters and rates");
  cli.add_flag("-v,--verbose", a->verbose, "every counter of every service, with its rate");
  return [a](Session& s) { return cmd_status(s, *a); };
}

namespace {

// The value for `key`, or nullptr.
template <class T>
const T* find_in(const std::map<std::string, T>& samples, const std::string& key) {
  auto it = samples.find(key);
  return it == samples.end() ? nullptr : &it->second;
}

int cmd_robots(Session& s, const ListArgs& a) {
  Latest<RobotPath> paths(s, dds::kRobotPath, [](const RobotPath& p) { return p.robot_id().to_string(); });
  Latest<PoseCorrection> corrections(s, dds::kPoseCorrection,
                                     [](const PoseCorrection& c) { return c.robot_id().to_string(); });
  Latest<RobotState> states(s, dds::kRobotState,
                            [](const RobotState& r) { return r.robot_id().to_string(); });
  if (!paths.ok() || !corrections.ok() || !states.ok()) return 1;
  // Paths and corrections are optional (no planner, no mapper): the window follows the robot states'
  // writer.
  listen_after_match(s, states, std::min<std::chrono::milliseconds>(s.timeout(), 1500ms));
  const auto path_of = paths.take();
  const auto correction_of = corrections.take();
  const auto robots = states.take();
  if (robots.empty()) return fail("no robot known on DDS domain " + std::to_string(s.domain()));
  std::vector<RobotSeen> seen;
  for (const auto& [id, st] : robots) {
    RobotSeen r{msg::from_idl(st), std::nullopt, std::nullopt};
    if (const auto* c = find_in(correction_of, id)) r.correction = msg::from_idl(*c);
    if (const auto* p = find_in(path_of, id)) r.path = msg::from_idl(*p);
    seen.push_back(std::move(r));
  }
  const int64_t now = now_ns();
  if (a.json) {
    std::printf("%s", robots_json(seen, now).c_str());
    return 0;
  }
  for (const RobotSeen& r : seen) {
    const msg::PoseCorrection* correction = r.correction ? &*r.correction : nullptr;
    const msg::RobotPath* path = r.path ? &*r.path : nullptr;
    std::printf("%s", format_robot(r.state, correction, path, now).c_str());
  }
  return 0;
}

}  // namespace

Handler add_robots(CLI::App& cli) {
  auto a = std::make_shared<ListArgs>();
  cli.add_flag("--json", a->json, "one JSON array: every robot with its goal and correction");
  return [a](Session& s) { return cmd_robots(s, *a); };
}

namespace {

int cmd_alerts(Session& s, const ListArgs& a) {
  Latest<Alert> alerts(s, dds::kAlert, [](const Alert& al) { return al.alert_id().to_string(); });
  if (!alerts.ok()) return 1;
  // The planners keep their alerts for late joiners: once one matched, they arrive at once.
  if (!wait_until([&] { return alerts.matched(); }, s.timeout()))
    return fail("no planner on DDS domain " + std::to_string(s.domain()) +
                " (alerts come from the planners)");
  wait_for_shutdown(std::min<std::chrono::milliseconds>(s.timeout(), 1000ms));
  std::vector<msg::Alert> shown;
  for (const auto& [id, alert] : alerts.take())
    if (a.all || alert.active()) shown.push_back(msg::from_idl(alert));
  const int64_t now = now_ns();
  if (a.json) {
    std::printf("%s", alerts_json(shown, now).c_str());
    return 0;
  }
  if (shown.empty()) std::printf("no %salerts\n", a.all ? "" : "active ");
  for (const msg::Alert& alert : shown) std::printf("%s", format_alert(alert, now).c_str());
  return 0;
}

}  // namespace

Handler add_alerts(CLI::App& cli) {
  auto a = std::make_shared<ListArgs>();
  cli.add_flag("--json", a->json, "one JSON array of alerts");
  cli.add_flag("--all", a->all, "cleared alerts too");
  return [a](Session& s) { return cmd_alerts(s, *a); };
}

namespace {

int cmd_forget(Session& s, const std::string& robot) {
  ForgetRobot f;
  f.request_id(s.next_goal_id());
  f.robot_id(robot);
  int reached = 0;
  const int rc = send(s, dds::kForgetRobot, f, {"gateway", "planner", "viewer"}, &reached);
  if (rc == 0)
    std::printf("robot %s forgotten by %d service(s) (gateways, planners, viewers); its map data stays\n",
                robot.c_str(), reached);
  return rc;
}

}  // namespace

Handler add_forget(CLI::App& cli) {
  auto robot = std::make_shared<std::string>();
  cli.add_option("robot", *robot, "robot id")->required();
  return [robot](Session& s) { return cmd_forget(s, *robot); };
}

namespace {

struct GoalArgs {
  std::string robot;
  std::string mode_name;
  std::vector<double> xy;
  double square_size = 1.0;
  bool centred = false;
};

int cmd_goal(Session& s, const GoalArgs& a) {
  const auto mode = msg::parse_goal_mode(a.mode_name);
  if (!mode)
    return usage_error("unknown mode '" + a.mode_name +
                       "' (idle, direct, planned, square, explore, home, stop)");
  const bool needs_target =
      *mode == msg::GoalMode::Direct || *mode == msg::GoalMode::Planned || *mode == msg::GoalMode::Square;
  if (needs_target && a.xy.size() != 2)
    return usage_error("mode " + a.mode_name + " needs a target: goal " + a.robot + " " + a.mode_name +
                       " X Y");
  NavGoal goal;
  goal.robot_id(a.robot == "all" ? "*" : a.robot);
  goal.goal_id(s.next_goal_id());
  goal.mode(msg::to_idl(*mode));
  goal.target(a.xy.size() == 2 ? point(a.xy[0], a.xy[1]) : point(0, 0));
  goal.square_size(a.square_size);
  goal.square_anchor(a.centred ? SQUARE_CENTRED : SQUARE_CORNER);
  const int rc = send(s, dds::kNavGoal, goal, {"planner"});
  if (rc == 0) std::printf("goal %s sent to %s\n", msg::goal_mode_name(*mode), a.robot.c_str());
  return rc;
}

}  // namespace

Handler add_goal(CLI::App& cli) {
  auto a = std::make_shared<GoalArgs>();
  cli.add_option("robot", a->robot, "robot id, or 'all'")->required();
  cli.add_option("mode", a->mode_name, "idle, direct, planned, square, explore, home or stop")->required();
  cli.add_option("xy", a->xy, "target x y in metres (direct, planned, square)")->expected(0, 2);
  cli.add_option("--size", a->square_size, "square side in metres")->check(CLI::PositiveNumber);
  cli.add_flag("--centred", a->centred, "square centred on the target instead of starting at it");
  return [a](Session& s) { return cmd_goal(s, *a); };
}

namespace {

struct MissionArgs {
  std::string robot;
  std::vector<double> xy;
  std::string file;
  bool loop = false;
};

int cmd_mission(Session& s, const MissionArgs& a) {
  if (a.robot == "all" || a.robot == "*") return usage_error("a mission is for one robot, not " + a.robot);
  if (a.file.empty() == a.xy.empty())
    return usage_error("give the waypoints as x1 y1 x2 y2 ... or --file FILE, not both");
  MissionSpec spec;
  if (a.file.empty()) {
    auto waypoints = waypoints_from_numbers(a.xy);
    if (!waypoints) return usage_error(waypoints.message());
    spec.waypoints = std::move(*waypoints);
  } else {
    auto loaded = load_mission_file(a.file);
    if (!loaded) return usage_error(loaded.message());
    spec = std::move(*loaded);
  }
  spec.loop = spec.loop || a.loop;
  if (spec.loop && spec.waypoints.size() < 2)
    return usage_error("a looped mission needs at least two waypoints");
  NavMission mission;
  mission.robot_id(a.robot);
  mission.mission_id(s.next_goal_id());
  mission.waypoints(spec.waypoints);
  mission.loop(spec.loop);
  mission.status(MISSION_ACTIVE);
  const int rc = send(s, dds::kNavMission, mission, {"planner"});
  if (rc == 0)
    std::printf("mission of %zu waypoint(s)%s sent to %s\n", spec.waypoints.size(),
                spec.loop ? ", looped," : "", a.robot.c_str());
  return rc;
}

}  // namespace

Handler add_mission(CLI::App& cli) {
  auto a = std::make_shared<MissionArgs>();
  cli.add_option("robot", a->robot, "robot id")->required();
  cli.add_option("xy", a->xy, "waypoints x1 y1 x2 y2 ... in metres (map frame)");
  cli.add_option("--file", a->file, "YAML mission file (waypoints: [[x, y], ...], loop: true|false)");
  cli.add_flag("--loop", a->loop, "start again at the first waypoint after the last (patrol)");
  return [a](Session& s) { return cmd_mission(s, *a); };
}

namespace {

int cmd_missions(Session& s) {
  std::mutex mutex;
  std::map<std::string, NavMission> seen;
  auto reader = dds::make_reader(s.participant(), dds::kNavMission, [&](const NavMission& m, const auto&) {
    std::lock_guard lock(mutex);
    auto [it, inserted] = seen.try_emplace(m.robot_id().to_string(), m);
    if (!inserted && !mission_behind(m, it->second)) it->second = m;
  });
  if (!reader) return fail(reader.message());
  if (wait_until([&] { return (*reader)->matched_writers() > 0; }, s.timeout()))
    wait_for_shutdown(std::min<std::chrono::milliseconds>(s.timeout(), 1500ms));
  reader->reset();
  if (seen.empty()) return fail("no mission known on DDS domain " + std::to_string(s.domain()));
  for (const auto& [id, m] : seen) std::printf("%s", format_mission(m).c_str());
  return 0;
}

}  // namespace

Handler add_missions(CLI::App&) {
  return cmd_missions;
}

namespace {

struct PathArgs {
  std::vector<double> ends;
  std::string algorithm = "astar";
  double budget_s = 1.0;
};

int cmd_path(Session& s, const PathArgs& a) {
  PathRequest req;
  req.client_id("slamctl:" + std::to_string(getpid()));
  req.start(point(a.ends[0], a.ends[1]));
  req.goal(point(a.ends[2], a.ends[3]));
  req.algorithm(a.algorithm);
  req.time_budget_s(a.budget_s);
  const auto reply = request(s, dds::kPathRequest, req, dds::kPathReply, "planner");
  if (!reply) return kExitFailure;
  std::printf("%s", format_path_reply(msg::from_idl(*reply)).c_str());
  return reply->status() == PLAN_OK ? 0 : 1;
}

}  // namespace

Handler add_path(CLI::App& cli) {
  auto a = std::make_shared<PathArgs>();
  cli.add_option("coordinates", a->ends, "start x y, goal x y (metres)")->expected(4)->required();
  cli.add_option("--algorithm", a->algorithm, "astar, fmtstar, rrtconnect, rrtstar or prmstar")
      ->capture_default_str();
  cli.add_option("--budget", a->budget_s, "time budget in seconds")->capture_default_str();
  return [a](Session& s) { return cmd_path(s, *a); };
}

namespace {

struct PoseArgs {
  std::string robot;
  double x = 0;
  double y = 0;
  double theta_deg = 0;
};

int cmd_pose(Session& s, const PoseArgs& a) {
  InitialPose req;
  req.robot_id(a.robot);
  req.pose().x(a.x);
  req.pose().y(a.y);
  req.pose().theta(wrap_angle(a.theta_deg * std::numbers::pi / 180.0));
  return map_request(s, dds::kInitialPose, req, "initial pose of " + a.robot + " set");
}

// CLI11 reads "nan" and "inf" as doubles; a pose must be finite.
std::string finite_number(std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size()) return "'" + text + "' is not a number";
  if (!std::isfinite(v)) return "'" + text + "' is not a finite number";
  return {};
}

}  // namespace

Handler add_pose(CLI::App& cli) {
  auto a = std::make_shared<PoseArgs>();
  const CLI::Validator finite(finite_number, "FINITE");
  cli.add_option("robot", a->robot, "robot id")->required();
  cli.add_option("x", a->x, "map x in metres")->required()->check(finite);
  cli.add_option("y", a->y, "map y in metres")->required()->check(finite);
  cli.add_option("theta", a->theta_deg,
                 "heading in degrees, counter-clockwise from +x (v1 robots: the rotation of their "
                 "odometry axes in the map)")
      ->required()
      ->check(finite);
  return [a](Session& s) { return cmd_pose(s, *a); };
}

namespace {

struct PlacementArgs {
  std::string verdict;
  std::string robot;
};

int cmd_placement(Session& s, const PlacementArgs& a) {
  PlacementAnswer req;
  req.robot_id(a.robot);
  req.verdict(a.verdict == "accept" ? PLACEMENT_ACCEPT : PLACEMENT_REJECT);
  return map_request(s, dds::kPlacementAnswer, req,
                     "placement of " + a.robot + (a.verdict == "accept" ? " accepted" : " rejected"));
}

}  // namespace

Handler add_placement(CLI::App& cli) {
  auto a = std::make_shared<PlacementArgs>();
  cli.add_option("verdict", a->verdict,
                 "accept: place a robot being placed where it was found; reject: it is not there, search on "
                 "(a placed robot is searched for again)")
      ->required()
      ->check(CLI::IsMember({"accept", "reject"}));
  cli.add_option("robot", a->robot, "robot id")->required();
  return [a](Session& s) { return cmd_placement(s, *a); };
}

}  // namespace slam::ctl
