#include "slamctl/commands.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <mutex>
#include <numbers>
#include <thread>

#include "common/core/clock.hpp"
#include "common/core/geometry.hpp"
#include "common/core/service_options.hpp"
#include "common/core/shutdown.hpp"
#include "common/fastdds/requester.hpp"
#include "slamctl/format.hpp"
#include "slamctl/mission_file.hpp"
#include "slamctl/record.hpp"

namespace slam::ctl {
namespace {

using namespace std::chrono_literals;

int fail(const std::string& why) {
  report_error("slamctl", why);
  return kExitFailure;
}

int usage_error(const std::string& why) {
  report_error("slamctl", why);
  return kExitUsage;
}

Point2 point(double x, double y) {
  Point2 p;
  p.x(x);
  p.y(y);
  return p;
}

bool wait_until(const std::function<bool()>& pred, std::chrono::milliseconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (!pred()) {
    if (std::chrono::steady_clock::now() >= until || shutdown_requested()) return false;
    std::this_thread::sleep_for(10ms);
  }
  return true;
}

// Writes one sample to whoever serves `topic` (waits for a reader first, then for its ack).
template <class T, class P>
int send(Session& s, const dds::Topic<T, P>& topic, const T& sample, const char* served_by) {
  auto writer = dds::make_writer(s.participant(), topic);
  if (!writer) return fail(writer.message());
  if (!(*writer)->wait_for_readers(s.timeout()))
    return fail(std::string("no ") + served_by + " on DDS domain " + std::to_string(s.domain()) +
                " (is it running?)");
  if (!(*writer)->write(sample)) return fail(std::string("could not write to ") + topic.info.name);
  if (!(*writer)->wait_for_acknowledgments(s.timeout()))
    return fail(std::string(served_by) + " did not acknowledge the request");
  return 0;
}

// Sends a request and waits for the reply with the same request id, sending it again on the retry
// schedule until then (the responder answers a repeat without executing it twice): no wait for a
// match first, so a responder that starts after slamctl still answers within the timeout.
template <class Req, class ReqP, class Rep, class RepP>
std::optional<Rep> request(Session& s, const dds::Topic<Req, ReqP>& req_topic, const Req& req,
                           const dds::Topic<Rep, RepP>& rep_topic, const char* served_by) {
  auto writer = dds::make_writer(s.participant(), req_topic);
  if (!writer) {
    fail(writer.message());
    return std::nullopt;
  }
  RetryPolicy policy;
  policy.timeout = s.timeout();
  auto requester = dds::Requester<Rep>::create(s.participant(), rep_topic, policy);
  if (!requester) {
    fail(requester.message());
    return std::nullopt;
  }
  auto reply = (*requester)->call(**writer, req);
  if (!reply)
    fail(std::string("no reply from ") + served_by + " on DDS domain " + std::to_string(s.domain()) +
         " within " + std::to_string(s.timeout().count()) + " ms (is it running?)");
  return reply;
}

// Sends a request the mapper answers with a MapReply and prints one line: the reply's text, or
// `done` when the mapper said nothing more than ok. 0 on MAP_OK, else one error line and 1.
template <class Req, class ReqP>
int map_request(Session& s, const dds::Topic<Req, ReqP>& req_topic, const Req& req, const std::string& done) {
  const auto reply = request(s, req_topic, req, dds::kMapReply, "mapper");
  if (!reply) return kExitFailure;
  if (reply->result() != MAP_OK)
    return fail(map_result_name(reply->result()) + ": " + reply->message().to_string());
  std::printf("%s\n", reply->message().size() == 0 ? done.c_str() : reply->message().c_str());
  return 0;
}

// The latest sample per key of a state topic (and the first, for rates), collected on the
// reader's thread.
template <class T>
class Latest {
 public:
  template <class P, class Key>
  Latest(Session& s, const dds::Topic<T, P>& topic, Key key) {
    auto reader = dds::make_reader(s.participant(), topic, [this, key](const T& sample, const auto&) {
      std::lock_guard lock(mutex_);
      const std::string k = key(sample);
      first_.try_emplace(k, sample);
      latest_[k] = sample;
    });
    if (!reader) {
      fail(reader.message());
      return;
    }
    reader_ = std::move(*reader);
  }
  bool ok() const { return reader_ != nullptr; }
  bool matched() const { return reader_ && reader_->matched_writers() > 0; }
  std::map<std::string, T> take() {
    reader_.reset();
    std::lock_guard lock(mutex_);
    return std::move(latest_);
  }
  // The first sample per key; call after take().
  std::map<std::string, T> take_first() {
    std::lock_guard lock(mutex_);
    return std::move(first_);
  }

 private:
  std::mutex mutex_;
  std::map<std::string, T> latest_;
  std::map<std::string, T> first_;
  std::unique_ptr<dds::Reader<T>> reader_;
};

// Listens for `listen` once `first` matched a writer (nothing to hear when none did within the
// timeout): discovery alone can take seconds, and the samples kept for late joiners arrive only after it.
template <class T>
void listen_after_match(Session& s, const Latest<T>& first, std::chrono::milliseconds listen) {
  if (wait_until([&] { return first.matched(); }, s.timeout())) wait_for_shutdown(listen);
}

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

// Each subcommand below: its handler, then `add_*`, which adds its arguments to its CLI11 subcommand and
// returns the handler bound to them; the table at the end names them in --help order.

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
  for (const auto& [key, hb] : latest) services.push_back(service_seen(first.at(key), hb));
  const int64_t now = now_ns();
  if (a.json) {
    std::printf("%s", services_json(services, now).c_str());
    return 0;
  }
  for (const ServiceSeen& seen : services) std::printf("%s", format_service(seen, now, a.verbose).c_str());
  return 0;
}

Handler add_status(CLI::App& cli) {
  auto a = std::make_shared<ListArgs>();
  cli.add_flag("--json", a->json, "one JSON array: every service with its counters and rates");
  cli.add_flag("-v,--verbose", a->verbose, "every counter of every service, with its rate");
  return [a](Session& s) { return cmd_status(s, *a); };
}

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
  const int64_t now = now_ns();
  if (a.json) {
    std::vector<RobotSeen> seen;
    for (const auto& [id, st] : robots) {
      RobotSeen r{st, std::nullopt, std::nullopt};
      if (const auto* c = find_in(correction_of, id)) r.correction = *c;
      if (const auto* p = find_in(path_of, id)) r.path = *p;
      seen.push_back(std::move(r));
    }
    std::printf("%s", robots_json(seen, now).c_str());
    return 0;
  }
  for (const auto& [id, st] : robots)
    std::printf("%s", format_robot(st, find_in(correction_of, id), find_in(path_of, id), now).c_str());
  return 0;
}

Handler add_robots(CLI::App& cli) {
  auto a = std::make_shared<ListArgs>();
  cli.add_flag("--json", a->json, "one JSON array: every robot with its goal and correction");
  return [a](Session& s) { return cmd_robots(s, *a); };
}

int cmd_alerts(Session& s, const ListArgs& a) {
  Latest<Alert> alerts(s, dds::kAlert, [](const Alert& al) { return al.alert_id().to_string(); });
  if (!alerts.ok()) return 1;
  // The planners keep their alerts for late joiners: once one matched, they arrive at once.
  if (!wait_until([&] { return alerts.matched(); }, s.timeout()))
    return fail("no planner on DDS domain " + std::to_string(s.domain()) +
                " (alerts come from the planners)");
  wait_for_shutdown(std::min<std::chrono::milliseconds>(s.timeout(), 1000ms));
  std::vector<Alert> shown;
  for (auto& [id, alert] : alerts.take())
    if (a.all || alert.active()) shown.push_back(std::move(alert));
  const int64_t now = now_ns();
  if (a.json) {
    std::printf("%s", alerts_json(shown, now).c_str());
    return 0;
  }
  if (shown.empty()) std::printf("no %salerts\n", a.all ? "" : "active ");
  for (const Alert& alert : shown) std::printf("%s", format_alert(alert, now).c_str());
  return 0;
}

Handler add_alerts(CLI::App& cli) {
  auto a = std::make_shared<ListArgs>();
  cli.add_flag("--json", a->json, "one JSON array of alerts");
  cli.add_flag("--all", a->all, "cleared alerts too");
  return [a](Session& s) { return cmd_alerts(s, *a); };
}

int cmd_forget(Session& s, const std::string& robot) {
  ForgetRobot f;
  f.request_id(s.next_goal_id());
  f.robot_id(robot);
  auto writer = dds::make_writer(s.participant(), dds::kForgetRobot);
  if (!writer) return fail(writer.message());
  if (!(*writer)->wait_for_readers(s.timeout()))
    return fail("no gateway, planner or viewer on DDS domain " + std::to_string(s.domain()) +
                " (is it running?)");
  if (!(*writer)->write(f)) return fail("could not write to " + std::string(topics::kForgetRobot.name));
  if (!(*writer)->wait_for_acknowledgments(s.timeout())) return fail("the services did not acknowledge");
  std::printf("robot %s forgotten by %d service(s) (gateways, planners, viewers); its map data stays\n",
              robot.c_str(), (*writer)->matched_readers());
  return 0;
}

Handler add_forget(CLI::App& cli) {
  auto robot = std::make_shared<std::string>();
  cli.add_option("robot", *robot, "robot id")->required();
  return [robot](Session& s) { return cmd_forget(s, *robot); };
}

struct GoalArgs {
  std::string robot;
  std::string mode_name;
  std::vector<double> xy;
  double square_size = 1.0;
  bool centred = false;
};

int cmd_goal(Session& s, const GoalArgs& a) {
  const auto mode = parse_goal_mode(a.mode_name);
  if (!mode)
    return usage_error("unknown mode '" + a.mode_name +
                       "' (idle, direct, planned, square, explore, home, stop)");
  const bool needs_target = *mode == GOAL_DIRECT || *mode == GOAL_PLANNED || *mode == GOAL_SQUARE;
  if (needs_target && a.xy.size() != 2)
    return usage_error("mode " + a.mode_name + " needs a target: goal " + a.robot + " " + a.mode_name +
                       " X Y");
  NavGoal goal;
  goal.robot_id(a.robot == "all" ? "*" : a.robot);
  goal.goal_id(s.next_goal_id());
  goal.mode(*mode);
  goal.target(a.xy.size() == 2 ? point(a.xy[0], a.xy[1]) : point(0, 0));
  goal.square_size(a.square_size);
  goal.square_anchor(a.centred ? SQUARE_CENTRED : SQUARE_CORNER);
  const int rc = send(s, dds::kNavGoal, goal, "planner");
  if (rc == 0) std::printf("goal %s sent to %s\n", goal_mode_name(*mode).c_str(), a.robot.c_str());
  return rc;
}

Handler add_goal(CLI::App& cli) {
  auto a = std::make_shared<GoalArgs>();
  cli.add_option("robot", a->robot, "robot id, or 'all'")->required();
  cli.add_option("mode", a->mode_name, "idle, direct, planned, square, explore, home or stop")->required();
  cli.add_option("xy", a->xy, "target x y in metres (direct, planned, square)")->expected(0, 2);
  cli.add_option("--size", a->square_size, "square side in metres")->check(CLI::PositiveNumber);
  cli.add_flag("--centred", a->centred, "square centred on the target instead of starting at it");
  return [a](Session& s) { return cmd_goal(s, *a); };
}

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
  const int rc = send(s, dds::kNavMission, mission, "planner");
  if (rc == 0)
    std::printf("mission of %zu waypoint(s)%s sent to %s\n", spec.waypoints.size(),
                spec.loop ? ", looped," : "", a.robot.c_str());
  return rc;
}

Handler add_mission(CLI::App& cli) {
  auto a = std::make_shared<MissionArgs>();
  cli.add_option("robot", a->robot, "robot id")->required();
  cli.add_option("xy", a->xy, "waypoints x1 y1 x2 y2 ... in metres (map frame)");
  cli.add_option("--file", a->file, "YAML mission file (waypoints: [[x, y], ...], loop: true|false)");
  cli.add_flag("--loop", a->loop, "start again at the first waypoint after the last (patrol)");
  return [a](Session& s) { return cmd_mission(s, *a); };
}

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

Handler add_missions(CLI::App&) {
  return cmd_missions;
}

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
  std::printf("%s", format_path_reply(*reply).c_str());
  return reply->status() == PLAN_OK ? 0 : 1;
}

Handler add_path(CLI::App& cli) {
  auto a = std::make_shared<PathArgs>();
  cli.add_option("coordinates", a->ends, "start x y, goal x y (metres)")->expected(4)->required();
  cli.add_option("--algorithm", a->algorithm, "astar, fmtstar, rrtconnect, rrtstar or prmstar")
      ->capture_default_str();
  cli.add_option("--budget", a->budget_s, "time budget in seconds")->capture_default_str();
  return [a](Session& s) { return cmd_path(s, *a); };
}

int cmd_map_file(Session& s, MapFileAction action, const std::string& yaml_path) {
  MapFileRequest req;
  req.action(action);
  req.yaml_path(yaml_path);
  return map_request(s, dds::kMapFileRequest, req,
                     (action == MAP_EXPORT ? "map saved to " : "map loaded from ") + yaml_path);
}

Handler add_map(CLI::App& cli) {
  auto file = std::make_shared<std::string>();
  cli.require_subcommand(1);
  auto* save = cli.add_subcommand("save", "export the map to FILE.yaml");
  save->add_option("file", *file, "YAML path")->required();
  auto* load = cli.add_subcommand("load", "import FILE.yaml as a prior");
  load->add_option("file", *file, "YAML path")->required();
  return
      [file, save](Session& s) { return cmd_map_file(s, save->parsed() ? MAP_EXPORT : MAP_IMPORT, *file); };
}

struct GridArgs {
  double resolution = 0.05;
  double width = 0;
  double height = 0;
  double inflation = -1;
  std::vector<double> origin;
  bool legacy = false;
};

int cmd_grid(Session& s, const GridArgs& a) {
  GridConfig c;
  c.resolution(a.resolution);
  c.width_m(a.width);
  c.height_m(a.height);
  c.origin(a.origin.size() == 2 ? point(a.origin[0], a.origin[1]) : point(0, 0));
  c.inflation_radius(a.inflation);
  c.legacy_mode(a.legacy);
  char done[160];
  std::snprintf(done, sizeof done, "grid set to %.3f m cells%s: the mapper rebuilt the map from its store",
                a.resolution, a.legacy ? " (legacy)" : "");
  return map_request(s, dds::kGridConfig, c, done);
}

Handler add_grid(CLI::App& cli) {
  auto a = std::make_shared<GridArgs>();
  cli.add_option("--resolution", a->resolution, "metres per cell")->check(CLI::PositiveNumber)->required();
  cli.add_option("--width", a->width, "metres (0: keep growing as robots explore)");
  cli.add_option("--height", a->height, "metres");
  cli.add_option("--origin", a->origin, "x y of the lower-left corner")->expected(2);
  cli.add_option("--inflation", a->inflation, "robot radius in metres for the restricted layer");
  cli.add_flag("--legacy", a->legacy, "2019 behaviour: points obstruct their cell, nothing is cleared");
  return [a](Session& s) { return cmd_grid(s, *a); };
}

int cmd_map_edit(Session& s, MapEditKind kind, const Point2& point, const std::string& robot) {
  MapEdit edit;
  edit.kind(kind);
  edit.point(point);
  edit.robot_id(robot);
  char done[160];
  switch (kind) {
    case EDIT_OBSTRUCT:
      std::snprintf(done, sizeof done, "cell at (%.2f, %.2f) obstructed", point.x(), point.y());
      break;
    case EDIT_UNOBSTRUCT:
      std::snprintf(done, sizeof done, "obstruction at (%.2f, %.2f) removed", point.x(), point.y());
      break;
    default:
      std::snprintf(done, sizeof done, "observations of %s deleted, map rebuilt", robot.c_str());
      break;
  }
  return map_request(s, dds::kMapEdit, edit, done);
}

// obstruct and unobstruct: one cell, x y.
Handler add_cell_edit(CLI::App& cli, MapEditKind kind) {
  auto cell = std::make_shared<std::vector<double>>();
  cli.add_option("xy", *cell, "x y in metres")->expected(2)->required();
  return [cell, kind](Session& s) { return cmd_map_edit(s, kind, point((*cell)[0], (*cell)[1]), ""); };
}

Handler add_obstruct(CLI::App& cli) {
  return add_cell_edit(cli, EDIT_OBSTRUCT);
}
Handler add_unobstruct(CLI::App& cli) {
  return add_cell_edit(cli, EDIT_UNOBSTRUCT);
}

Handler add_reset(CLI::App& cli) {
  auto robot = std::make_shared<std::string>();
  cli.add_option("robot", *robot, "robot id")->required();
  return [robot](Session& s) { return cmd_map_edit(s, EDIT_RESET_ROBOT, point(0, 0), *robot); };
}

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
  if (topic == topics::kRobotObservation.name) return echo(s, dds::kRobotObservation, count);
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
      {"grid", "change the grid layout (the mapper rebuilds from its store)", add_grid},
      {"obstruct", "mark the cell at x y occupied by hand", add_obstruct},
      {"unobstruct", "remove a manual obstruction at x y", add_unobstruct},
      {"reset", "delete every observation of a robot and rebuild the map", add_reset},
      {"pose", "set a robot's pose in the map (initial pose): pose ROBOT X Y THETA_DEG", add_pose},
      {"sim", "control the simulator", add_sim},
      {"echo", "print samples of a topic (see docs/topics.md) until Ctrl-C", add_echo},
      {"record", "record every topic (or --topics) to an MCAP file Foxglove opens", add_record},
      {"replay", "publish a recorded MCAP file again, with its timing (--rate to scale)", add_replay},
  };
  return table;
}

}  // namespace slam::ctl
