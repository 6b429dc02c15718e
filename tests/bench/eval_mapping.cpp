// eval_mapping: runs the whole system (mosquitto, gateway, mapper, planner, simulator) with
// simulated robots exploring one world faster than real time, and scores it against the
// simulator's ground truth: trajectory error (ATE) of corrected and raw poses, how close robots
// truly are to waypoints the planner counts reached, the exported map against the true walls, and
// whether the mapper's loop closures moved robots towards the truth (false closures); with the
// mapper's SLAM counters at the end of the run. With --patrol, once every robot is home from
// exploring, each drives a looped mission through random places of the world for the rest of the
// run, as robots do in use once a building is mapped, and that part is scored apart.
// Writes <out>/<name>.json (one object), <name>.png (the map with the true walls over it), the
// exported <name>.yaml/.pgm, and the recording eval_replay takes (<name>.db, <name>.truth). See
// docs/mapping-quality.md; scripts/bench.sh runs the matrix.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "common/fastdds/fast_topics.hpp"
#include "eval/run_recorder.hpp"
#include "eval/run_score.hpp"
#include "eval/truth_log.hpp"
#include "eval/world_places.hpp"
#include "eval_mapping_tap.hpp"
#include "process_group.hpp"
#include "simulator/core/config.hpp"
#include "simulator/core/world_loader.hpp"

namespace slam::bench {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

constexpr double kMaxTruthRateHz = 50.0;  // the largest --truth-rate the simulator accepts
constexpr uint64_t kExploreGoalId = 1;
// A patrol: this many places, each at least kPatrolLeg_m in a straight line from the one before and
// kPatrolClearance_m from walls (eval_coordination's figures).
constexpr size_t kPatrolPlaces = 8;
constexpr double kPatrolLeg_m = 2.0;
constexpr double kPatrolClearance_m = 0.35;

struct EvalOptions {
  std::string world = "office";
  std::string protocol = "v1";
  double drift = 0.02;  // the simulator's default
  double speed = 8.0;
  double duration_s = 1200.0;  // simulated, from the exploration goal on
  int robots = 3;
  uint64_t seed = 1;
  bool align = false;
  std::string odom_frame;  // passed to the simulator when set
  std::vector<std::string> sim_args, mapper_args, planner_args;
  std::string mapper_bin;  // default: this build's slam-mapper; another build's, to compare two versions
  // The mapper's log level; its log is kept as <out>/<name>.mapper.log ("info" lists every loop
  // closure with the match's figures, to find a false closure's gate).
  std::string mapper_log_level = "warn";
  // The planner's, kept as <out>/<name>.planner.log ("info" lists the robots sent back to
  // re-localise).
  std::string planner_log_level = "warn";
  std::string out_dir = "build/bench/mapping";
  std::string name;                 // default: from world, protocol, drift and the extra arguments
  double reach_tolerance_m = 0.20;  // the planner's 0.15 m plus motion between its decision and the sample
  double false_closure_increase_m = 0.10;  // a loop correction adding more error than this is false
  int pixels_per_cell = 2;
  bool patrol = false;  // after exploration, looped missions through random places (scored apart)
  // A map (ROS YAML) imported into the mapper's store before it starts: the building mapped
  // earlier, for a run that localises on it (--mapper-arg=--localise-only).
  std::string prior_yaml;
};

// A robot placed farther than this from where it truly was is placed wrongly.
constexpr double kWrongPlacement_m = 0.5;

std::string default_name(const EvalOptions& o) {
  std::string name = fmt::format("{}-{}-drift{}", o.world, o.protocol, o.drift);
  for (const auto* args : {&o.sim_args, &o.mapper_args})
    for (const std::string& a : *args) name += "-" + a;
  if (!o.odom_frame.empty()) name += "-odom" + o.odom_frame;
  if (o.patrol) name += "-patrol";
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.') c = '_';
  return name;
}

// "on"/"off" when the mapper arguments say so ("--slam X" or "--slam=X"), else what the run showed.
std::string slam_label(const std::vector<std::string>& mapper_args, size_t corrected_robots) {
  for (size_t i = 0; i < mapper_args.size(); ++i) {
    if (mapper_args[i] == "--slam" && i + 1 < mapper_args.size()) return mapper_args[i + 1];
    if (mapper_args[i].starts_with("--slam=")) return mapper_args[i].substr(7);
  }
  return corrected_robots > 0 ? "on" : "off";
}

class Evaluation {
 public:
  explicit Evaluation(const EvalOptions& o)
      : o_(o), recorder_(static_cast<int64_t>(1e9 / o.speed), o.reach_tolerance_m) {}

  Result<nlohmann::json> run() {
    if (o_.patrol) {
      if (o_.align || o_.odom_frame == "start")
        return Error{
            "--patrol sends robots to world coordinates: it needs the world odometry frame (no --align, "
            "no --odom-frame start)"};
      auto world = sim::load_world(o_.world);
      if (!world) return Error{"--patrol: " + world.message()};
      patrol_world_ = std::move(*world);
    }
    SLAM_TRY(start_processes());
    auto tap = SystemTap::create(lease_.id(), recorder_);
    if (!tap) return tap.error();
    tap_ = std::move(*tap);
    SLAM_TRY(wait_for("every robot's truth and state, the world and the planner's goal reader", 90s, [&] {
      return recorder_.robots_seen() >= static_cast<size_t>(o_.robots) &&
             recorder_.robots_published() >= static_cast<size_t>(o_.robots) && tap_->world().has_value() &&
             tap_->counter("simulator", "steps") >= 0 && tap_->goals().wait_for_readers(10ms);
    }));

    const double step_s = sim::SimulationConfig{}.dt;
    const int64_t steps0 = tap_->counter("simulator", "steps");
    NavGoal goal;
    goal.robot_id("*");
    goal.goal_id(kExploreGoalId);
    goal.mode(GOAL_EXPLORE);
    if (!tap_->goals().write(goal)) return Error{"writing the exploration goal failed"};
    recorder_.start();
    const auto t0 = Clock::now();
    const auto budget = std::chrono::duration<double>(3.0 * o_.duration_s / o_.speed + 60.0);
    double simulated_s = 0.0;
    auto next_report = t0 + 30s;
    while (simulated_s < o_.duration_s) {
      SLAM_TRY(check_running());
      if (Clock::now() - t0 > budget)
        return Error{
            fmt::format("only {:.0f} of {:.0f} simulated seconds after {:.0f} s: the simulator fell behind",
                        simulated_s, o_.duration_s, budget.count())};
      std::this_thread::sleep_for(200ms);
      simulated_s = static_cast<double>(tap_->counter("simulator", "steps") - steps0) * step_s;
      if (o_.patrol && !patrol_ && tap_->goal_ended(kExploreGoalId, static_cast<size_t>(o_.robots)))
        SLAM_TRY(start_patrol(simulated_s));
      if (Clock::now() >= next_report) {
        std::fprintf(stderr, "eval_mapping: %s: %.0f of %.0f simulated s\n", name().c_str(), simulated_s,
                     o_.duration_s);
        next_report += 30s;
      }
    }
    recorder_.stop();
    const double wall_s = std::chrono::duration<double>(Clock::now() - t0).count();

    std::filesystem::create_directories(o_.out_dir);
    const std::string yaml = std::filesystem::absolute(o_.out_dir + "/" + name() + ".yaml").string();
    SLAM_TRY(export_map(yaml));
    SLAM_TRY(keep_recording());
    std::ofstream(o_.out_dir + "/" + name() + ".mapper.log") << group_.log("mapper");
    std::ofstream(o_.out_dir + "/" + name() + ".planner.log") << group_.log("planner");
    auto map = read_ros_map(yaml);
    if (!map) return Error{"reading the exported map: " + map.message()};
    return score(*map, yaml, simulated_s, wall_s);
  }

  std::string name() const { return o_.name.empty() ? default_name(o_) : o_.name; }

 private:
  Status start_processes() {
    const std::string mapper = o_.mapper_bin.empty() ? testkit::bin_path("slam-mapper") : o_.mapper_bin;
    if (!o_.prior_yaml.empty()) {
      group_.start("import", {mapper, "--store", group_.dir() + "/map.db", "--import", o_.prior_yaml});
      if (group_.wait_exit("import", 60s) != 0)
        return Error{"importing " + o_.prior_yaml + " failed:\n" + group_.log("import")};
    }
    const std::string domain = std::to_string(lease_.id());
    const std::string broker = "tcp://127.0.0.1:" + std::to_string(group_.start_mosquitto());
    const auto with = [](std::vector<std::string> argv, const std::vector<std::string>& extra) {
      argv.insert(argv.end(), extra.begin(), extra.end());
      return argv;
    };
    // The pose stream at its real-time rate in simulated time (0.1 s): at --speed 4 a 0.1 s digest
    // would show the planner each robot 0.4 simulated seconds late, 20 cm at full speed.
    group_.start("gateway", {testkit::bin_path("slam-gateway"), "--domain", domain, "--broker", broker,
                             "--digest-period-s", fmt::format("{}", std::max(0.01, 0.1 / o_.speed)),
                             "--log-level", "warn"});
    group_.start("mapper", with({mapper, "--domain", domain, "--store", group_.dir() + "/map.db",
                                 "--log-level", o_.mapper_log_level},
                                o_.mapper_args));
    group_.start("planner", with({testkit::bin_path("slam-planner"), "--domain", domain, "--goal-store",
                                  group_.dir() + "/goals.json", "--log-level", o_.planner_log_level},
                                 o_.planner_args));
    std::vector<std::string> sim = {
        testkit::bin_path("slam-simulator"), "--domain", domain, "--broker", broker, "--world", o_.world,
        "--robots", std::to_string(o_.robots), "--protocol", o_.protocol, "--drift",
        fmt::format("{}", o_.drift), "--seed", std::to_string(o_.seed), "--speed",
        fmt::format("{}", o_.speed),
        // A truth sample per simulated step, up to the simulator's
        // limit: arrivals pair with the next one; the ATE takes one a second.
        "--truth-rate", fmt::format("{}", std::min(kMaxTruthRateHz, o_.speed / sim::SimulationConfig{}.dt)),
        "--log-level", "warn"};
    if (!o_.odom_frame.empty()) sim.insert(sim.end(), {"--odom-frame", o_.odom_frame});
    group_.start("simulator", with(sim, o_.sim_args));
    return Status::ok();
  }

  // Each robot gets a looped mission from where it is now; from here on its samples are the patrol's.
  Status start_patrol(double simulated_s) {
    const std::vector<Vec2> places =
        reachable_places(*patrol_world_, recorder_.true_starts().front(), kPatrolClearance_m);
    if (places.empty()) return Error{"--patrol: no reachable place in world " + o_.world};
    patrol_ = Patrol{simulated_s, recorder_.samples().size(), recorder_.arrivals().size()};
    std::mt19937_64 rng(o_.seed);
    uint64_t mission_id = 1;
    for (const auto& [robot, track] : recorder_.true_tracks()) {
      NavMission mission;
      mission.robot_id(robot);
      mission.mission_id(mission_id++);
      std::vector<Point2> waypoints;
      for (const Vec2& p : patrol_route(places, track.back(), kPatrolPlaces, kPatrolLeg_m, rng)) {
        Point2 w;
        w.x(p.x);
        w.y(p.y);
        waypoints.push_back(w);
      }
      mission.waypoints(waypoints);
      mission.loop(true);
      mission.status(MISSION_ACTIVE);
      if (!tap_->missions().wait_for_readers(10s) || !tap_->missions().write(mission))
        return Error{"the planner does not take missions"};
    }
    std::fprintf(stderr, "eval_mapping: %s: exploration done after %.0f simulated s; patrolling\n",
                 name().c_str(), simulated_s);
    return Status::ok();
  }

  Status check_running() {
    for (const char* p : {"mosquitto", "gateway", "mapper", "planner", "simulator"}) {
      if (group_.running(p)) continue;
      const std::string log = group_.log(p);
      return Error{fmt::format("{} exited:\n{}", p, log.size() > 2000 ? log.substr(log.size() - 2000) : log)};
    }
    return Status::ok();
  }

  Status wait_for(const std::string& what, std::chrono::seconds timeout, const std::function<bool()>& ready) {
    const auto until = Clock::now() + timeout;
    while (!ready()) {
      SLAM_TRY(check_running());
      if (Clock::now() > until) return Error{fmt::format("no {} within {} s", what, timeout.count())};
      std::this_thread::sleep_for(100ms);
    }
    return Status::ok();
  }

  Status export_map(const std::string& yaml) {
    MapFileRequest request;
    request.request_id(1);
    request.action(MAP_EXPORT);
    request.yaml_path(yaml);
    if (!tap_->files().wait_for_readers(30s) || !tap_->files().write(request))
      return Error{"the mapper does not take map file requests"};
    SLAM_TRY(wait_for("reply to the map export", 120s, [&] { return tap_->reply(1).has_value(); }));
    const MapReply reply = *tap_->reply(1);
    if (reply.result() != MAP_OK) return Error{"map export failed: " + reply.message().to_string()};
    return Status::ok();
  }

  // The run's raw observations (the mapper's store, closed by stopping the mapper) and its sampled
  // truth, as <name>.db and <name>.truth: eval_replay runs the pose correction on them offline.
  Status keep_recording() {
    group_.stop("mapper", SIGTERM);
    const std::string base = o_.out_dir + "/" + name();
    std::error_code ec;
    std::filesystem::copy_file(group_.dir() + "/map.db", base + ".db",
                               std::filesystem::copy_options::overwrite_existing, ec);
    if (ec) return Error{"keeping the mapper's store as " + base + ".db: " + ec.message()};
    std::filesystem::remove(base + ".db-wal", ec);
    if (std::filesystem::exists(group_.dir() + "/map.db-wal"))  // the mapper did not close it: keep the log
      std::filesystem::copy_file(group_.dir() + "/map.db-wal", base + ".db-wal", ec);
    return write_truth_log(base + ".truth", recorder_.truth_samples());
  }

  Result<nlohmann::json> score(const MapImage& map, const std::string& yaml, double simulated_s,
                               double wall_s) {
    const ScoreOptions options{o_.align, o_.false_closure_increase_m, o_.pixels_per_cell};
    const std::string png = yaml.substr(0, yaml.size() - 5) + ".png";
    auto run = score_run(recorder_, map, walls_of(*tap_->world()), options, png);
    if (!run) return run.error();
    // Published states: aligned like the corrected poses (both are in the map frame).
    std::vector<Vec2> published, truth;
    for (const auto& [p, t] : recorder_.published_vs_truth()) {
      published.push_back(run->ate.alignment.transform(p));
      truth.push_back(t);
    }
    std::vector<double> goal_true, goal_reported;
    for (const GoalArrival& a : recorder_.arrivals()) {
      goal_true.push_back(a.true_distance_m);
      goal_reported.push_back(a.reported_distance_m);
    }

    const size_t corrected = recorder_.corrected_robots();
    nlohmann::json j;
    j["name"] = name();
    j["world"] = o_.world;
    j["protocol"] = o_.protocol;
    j["drift"] = o_.drift;
    j["sim_args"] = o_.sim_args;
    j["mapper_args"] = o_.mapper_args;
    if (!o_.mapper_bin.empty()) j["mapper_bin"] = o_.mapper_bin;
    j["planner_args"] = o_.planner_args;
    j["odom_frame"] = o_.odom_frame.empty() ? "world" : o_.odom_frame;
    j["slam"] = slam_label(o_.mapper_args, corrected);
    j["corrected_robots"] = corrected;
    j["robots"] = o_.robots;
    j["seed"] = o_.seed;
    j["speed"] = o_.speed;
    j["simulated_s"] = simulated_s;
    j["wall_s"] = wall_s;
    j["achieved_speed"] = simulated_s / wall_s;
    j["simulator_loop_overruns"] = tap_->counter("simulator", "loop_overruns");
    j["mapper_dropped"] = tap_->counter("mapper", "dropped");
    add_to_json(*run, recorder_, options, j);
    j["ate_published"] = to_json(position_errors(published, truth));
    j["goal_true"] = to_json(summarise(goal_true));
    j["goal_reported"] = to_json(summarise(goal_reported));
    j["after_exploration"] = o_.patrol ? "patrol" : "idle";
    j["patrol"] = patrol_json(goal_true);
    j["placement"] = placement_json();
    j["slam_counters"] = tap_->counters("mapper", "slam_");
    j["image"] = std::filesystem::path(png).filename().string();
    j["map_yaml"] = std::filesystem::path(yaml).filename().string();
    return j;
  }

  // When each robot was first placed on the map, how far off, and the trajectory error from then on.
  nlohmann::json placement_json() const {
    std::vector<double> after_s, error_m;
    int wrong = 0;
    for (const RobotPlacement& p : recorder_.placements()) {
      after_s.push_back(p.after_s);
      error_m.push_back(p.error_m);
      wrong += p.error_m > kWrongPlacement_m ? 1 : 0;
    }
    const std::vector<TrajectorySample> placed = recorder_.placed_samples();
    return {{"robots", o_.robots},
            {"placed", after_s.size()},
            {"wrong", wrong},
            {"wrong_beyond_m", kWrongPlacement_m},
            {"after_s", after_s},
            {"error_m", to_json(summarise(error_m))},
            {"ate_after_placement", to_json(trajectory_errors(placed, false).corrected)}};
  }

  // The part of the run after exploration (null without --patrol, or when exploration did not end).
  nlohmann::json patrol_json(std::span<const double> goal_true) const {
    if (!patrol_) return nullptr;
    const std::vector<TrajectorySample> samples = recorder_.samples();
    const TrajectoryErrors errors =
        trajectory_errors(std::span(samples).subspan(std::min(patrol_->first_sample, samples.size())), false);
    return {{"started_s", patrol_->started_s},
            {"places", kPatrolPlaces},
            {"ate_corrected", to_json(errors.corrected)},
            {"ate_raw", to_json(errors.raw)},
            {"goal_true",
             to_json(summarise(goal_true.subspan(std::min(patrol_->first_arrival, goal_true.size()))))}};
  }

  struct Patrol {
    double started_s = 0.0;  // simulated, from the exploration goal on
    size_t first_sample = 0;
    size_t first_arrival = 0;
  };

  EvalOptions o_;
  RunRecorder recorder_;
  std::optional<sim::World> patrol_world_;
  std::optional<Patrol> patrol_;
  testkit::DomainLease lease_;
  testkit::ProcessGroup group_;
  std::unique_ptr<SystemTap> tap_;
};

}  // namespace
}  // namespace slam::bench

int main(int argc, char** argv) {
  using slam::bench::EvalOptions;
  EvalOptions o;
  CLI::App app{"eval_mapping: one run of the whole system scored against the simulator's ground truth"};
  app.add_option("--world", o.world, "simulator world: office, maze, track, rooms or a file")
      ->capture_default_str();
  app.add_option("--protocol", o.protocol, "robot protocol")
      ->check(CLI::IsMember({"v1", "v2"}))
      ->capture_default_str();
  app.add_option("--drift", o.drift, "simulator odometry drift (m per sqrt(m))")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  app.add_option("--speed", o.speed, "simulated seconds per wall-clock second")
      ->check(CLI::Range(0.1, 100.0))
      ->capture_default_str();
  app.add_option("--duration", o.duration_s,
                 "simulated seconds from the exploration goal on (a patrol included)")
      ->check(CLI::Range(1.0, 86400.0))
      ->capture_default_str();
  app.add_option("--robots", o.robots, "simulated robots")->check(CLI::Range(1, 100))->capture_default_str();
  app.add_option("--seed", o.seed, "simulator random seed")->capture_default_str();
  app.add_option("--prior", o.prior_yaml,
                 "a map (ROS YAML) imported into the mapper's store before it starts (a building mapped "
                 "earlier: add --mapper-arg=--localise-only to localise on it)");
  app.add_flag("--align", o.align,
               "fit the map frame to the world (rigid 2-D) before scoring; for --odom-frame start");
  app.add_option("--odom-frame", o.odom_frame, "passed to the simulator (world or start)");
  app.add_option("--sim-arg", o.sim_args,
                 "extra simulator argument (repeat: --sim-arg=--heading-drift --sim-arg=0.02)")
      ->allow_extra_args(false);
  app.add_option("--mapper-arg", o.mapper_args, "extra mapper argument (repeat)")->allow_extra_args(false);
  app.add_option("--mapper-bin", o.mapper_bin,
                 "slam-mapper executable to run (default: this build's; a saved one compares two versions)");
  app.add_option("--mapper-log-level", o.mapper_log_level,
                 "the mapper's log level; its log is kept as <out>/<name>.mapper.log")
      ->capture_default_str();
  app.add_option("--planner-arg", o.planner_args, "extra planner argument (repeat)")->allow_extra_args(false);
  app.add_option("--planner-log-level", o.planner_log_level,
                 "the planner's log level; its log is kept as <out>/<name>.planner.log")
      ->capture_default_str();
  app.add_option("--out", o.out_dir, "directory of the results")->capture_default_str();
  app.add_option("--name", o.name,
                 "run name (file names); default from world, protocol, drift and extra arguments");
  app.add_option("--reach-tolerance", o.reach_tolerance_m,
                 "distance (m) at which a vanished path counts as reached")
      ->check(CLI::Range(0.01, 5.0))
      ->capture_default_str();
  app.add_option("--false-closure-increase", o.false_closure_increase_m,
                 "error increase (m) beyond which a loop-closure correction counts as false")
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  app.add_flag("--patrol", o.patrol,
               "once every robot is home from exploring, send each a looped mission through random places "
               "for the rest of the run, scored apart (\"patrol\" in the JSON)");
  app.add_option("--pixels-per-cell", o.pixels_per_cell, "image scale")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  try {
    slam::bench::Evaluation evaluation(o);
    auto result = evaluation.run();
    if (!result) {
      std::fprintf(stderr, "eval_mapping: %s: %s\n", evaluation.name().c_str(), result.message().c_str());
      return 1;
    }
    const std::string json_path = o.out_dir + "/" + evaluation.name() + ".json";
    std::ofstream(json_path) << result->dump(2) << "\n";
    std::printf("%s\n", result->dump(2).c_str());
    std::fprintf(stderr, "eval_mapping: wrote %s\n", json_path.c_str());
    return 0;
  } catch (const std::exception& e) {  // process start-up (the harness throws when it cannot start)
    std::fprintf(stderr, "eval_mapping: %s\n", e.what());
    return 1;
  }
}
