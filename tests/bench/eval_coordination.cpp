// eval_coordination: the whole system (mosquitto, gateway, mapper, planner, simulator) with N
// simulated robots, each sent to one random reachable place after another (a planned goal; a new
// one when it arrives, fails or runs out of time), for a simulated duration. Measures what fleet
// coordination is for: robot-robot contacts (the simulator's robot_contacts counter), the longest
// wait the planner imposed on any robot, the longest time one goal took, goals that ran out of time
// (a robot stuck for good), and targets reached per simulated minute. Run it with --coordination on
// and off to compare; docs/performance.md ("Fleet coordination") has the figures.
// Run: build/bin/eval_coordination --world maze --robots 10 --duration 1200 --coordination on
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <thread>

#include "common/fastdds/fast_topics.hpp"
#include "eval/world_places.hpp"
#include "process_group.hpp"
#include "simulator/core/builtin_worlds.hpp"
#include "simulator/core/config.hpp"

namespace slam::bench {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

struct EvalOptions {
  std::string world = "maze";
  int robots = 10;
  double speed = 4.0;
  double duration_s = 1200.0;  // simulated
  std::string coordination = "on";
  uint64_t seed = 1;
  double goal_timeout_s = 240.0;  // simulated: a goal not reached by then counts as stuck
  double min_trip_m = 2.0;        // targets at least this far (straight line) from the robot
  double clearance_m = 0.35;      // targets keep this far from walls
  std::vector<std::string> planner_args;
  std::string planner_bin;  // another build's planner (before/after comparisons); default: this build's
  std::string out;          // JSON file; stdout always gets the JSON
};

// What the run hears on DDS; written by listener threads.
class Tap {
 public:
  static Result<std::unique_ptr<Tap>> create(int domain) {
    std::unique_ptr<Tap> tap(new Tap);
    auto participant = dds::Participant::create(domain, "eval-coordination");
    if (!participant) return Error{"DDS participant: " + participant.message()};
    tap->participant_ = std::move(*participant);
    auto digests = dds::make_reader(
        *tap->participant_, dds::kFleetDigest, [t = tap.get()](const FleetDigest& d, const auto&) {
          std::lock_guard lock(t->mutex_);
          for (const DigestRobot& r : d.robots())
            t->positions_[r.robot_id().to_string()] = Vec2{r.pose().x(), r.pose().y()};
        });
    if (!digests) return digests.error();
    tap->digests_ = std::move(*digests);
    auto paths = dds::make_reader(*tap->participant_, dds::kRobotPath,
                                  [t = tap.get()](const RobotPath& p, const auto&) {
                                    std::lock_guard lock(t->mutex_);
                                    t->status_[p.robot_id().to_string()] = {p.goal_id(), p.status()};
                                  });
    if (!paths) return paths.error();
    tap->paths_ = std::move(*paths);
    auto beats = dds::make_reader(*tap->participant_, dds::kHeartbeat,
                                  [t = tap.get()](const Heartbeat& h, const auto&) {
                                    std::lock_guard lock(t->mutex_);
                                    auto& counters = t->counters_[h.service().to_string()];
                                    for (const Counter& c : h.counters())
                                      counters[c.name().to_string()] = c.value();
                                  });
    if (!beats) return beats.error();
    tap->heartbeats_ = std::move(*beats);
    auto goals = dds::make_writer(*tap->participant_, dds::kNavGoal);
    if (!goals) return goals.error();
    tap->goals_ = std::move(*goals);
    return tap;
  }

  int64_t counter(const std::string& service, const std::string& name) const {
    std::lock_guard lock(mutex_);
    const auto s = counters_.find(service);
    if (s == counters_.end()) return -1;
    const auto c = s->second.find(name);
    return c == s->second.end() ? -1 : c->second;
  }
  std::map<std::string, Vec2> positions() const {
    std::lock_guard lock(mutex_);
    return positions_;
  }
  // The latest goal id and status reported for the robot.
  std::pair<uint64_t, GoalStatus> status(const std::string& id) const {
    std::lock_guard lock(mutex_);
    const auto it = status_.find(id);
    return it == status_.end() ? std::pair<uint64_t, GoalStatus>{0, GOAL_STATUS_NONE} : it->second;
  }
  dds::Writer<NavGoal>& goals() { return *goals_; }

 private:
  Tap() = default;
  // Written by the listeners: declared before the readers so it outlives them (members are
  // destroyed in reverse order).
  mutable std::mutex mutex_;
  std::map<std::string, Vec2> positions_;
  std::map<std::string, std::pair<uint64_t, GoalStatus>> status_;
  std::map<std::string, std::map<std::string, int64_t>> counters_;
  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<dds::Reader<FleetDigest>> digests_;
  std::unique_ptr<dds::Reader<RobotPath>> paths_;
  std::unique_ptr<dds::Reader<Heartbeat>> heartbeats_;
  std::unique_ptr<dds::Writer<NavGoal>> goals_;
};

struct RobotRun {
  uint64_t goal_id = 0;
  double sent_s = 0.0;  // simulated time the goal went out
};

class Evaluation {
 public:
  explicit Evaluation(const EvalOptions& o) : o_(o), rng_(o.seed) {}

  Result<nlohmann::json> run() {
    auto world = sim::builtin_world(o_.world);
    if (!world) return world.error();
    start_processes(world->bounds());
    auto tap = Tap::create(lease_.id());
    if (!tap) return tap.error();
    tap_ = std::move(*tap);
    const auto ready = [&] {
      return tap_->positions().size() >= static_cast<size_t>(o_.robots) &&
             tap_->counter("simulator", "steps") >= 0 && tap_->counter("planner", "goals_accepted") >= 0 &&
             tap_->goals().wait_for_readers(10ms);
    };
    if (!testkit::wait_until(ready, 90s))
      return Error{"the robots, the simulator or the planner did not show up in 90 s"};
    const auto start_positions = tap_->positions();
    places_ = reachable_places(*world, start_positions.begin()->second, o_.clearance_m);
    if (places_.empty()) return Error{"no reachable place in world " + o_.world};

    const double step_s = sim::SimulationConfig{}.dt;
    const int64_t steps0 = tap_->counter("simulator", "steps");
    const int64_t contacts0 = tap_->counter("simulator", "robot_contacts");
    const auto t0 = Clock::now();
    const auto budget = std::chrono::duration<double>(4.0 * o_.duration_s / o_.speed + 60.0);
    double sim_s = 0.0, longest_goal_s = 0.0;
    uint64_t next_goal = 1000, reached = 0, failed = 0, timed_out = 0;
    std::map<std::string, RobotRun> runs;
    auto next_report = t0 + 30s;
    while (sim_s < o_.duration_s) {
      for (const char* p : {"mosquitto", "gateway", "mapper", "planner", "simulator"})
        if (!group_.running(p)) return Error{fmt::format("{} exited; log in {}", p, group_.dir())};
      if (Clock::now() - t0 > budget)
        return Error{fmt::format("simulator fell behind: {:.0f} s simulated", sim_s)};
      std::this_thread::sleep_for(100ms);
      sim_s = static_cast<double>(tap_->counter("simulator", "steps") - steps0) * step_s;
      for (const auto& [id, position] : tap_->positions()) {
        RobotRun& r = runs[id];
        const auto [goal_id, status] = tap_->status(id);
        bool next = r.goal_id == 0;
        if (r.goal_id != 0 && goal_id == r.goal_id && status == GOAL_STATUS_REACHED) {
          ++reached;
          longest_goal_s = std::max(longest_goal_s, sim_s - r.sent_s);
          next = true;
        } else if (r.goal_id != 0 && goal_id == r.goal_id && status == GOAL_STATUS_FAILED) {
          ++failed;
          next = true;
        } else if (r.goal_id != 0 && sim_s - r.sent_s > o_.goal_timeout_s) {
          ++timed_out;
          longest_goal_s = std::max(longest_goal_s, sim_s - r.sent_s);
          next = true;
        }
        if (!next) continue;
        r.goal_id = ++next_goal;
        r.sent_s = sim_s;
        send_goal(id, r.goal_id, pick_place(places_, position, o_.min_trip_m, rng_));
      }
      if (Clock::now() >= next_report) {
        std::fprintf(stderr, "eval_coordination: %s %s: %.0f of %.0f simulated s, %llu reached\n",
                     o_.world.c_str(), o_.coordination.c_str(), sim_s, o_.duration_s,
                     static_cast<unsigned long long>(reached));
        next_report += 30s;
      }
    }
    const double wall_s = std::chrono::duration<double>(Clock::now() - t0).count();
    // Goals still running at the end: the longest of them counts too (a robot stuck until the end).
    for (const auto& [id, r] : runs) longest_goal_s = std::max(longest_goal_s, sim_s - r.sent_s);
    const double achieved_speed = sim_s / wall_s;
    nlohmann::json j;
    j["world"] = o_.world;
    j["robots"] = o_.robots;
    j["coordination"] = o_.coordination;
    j["seed"] = o_.seed;
    j["simulated_s"] = sim_s;
    j["wall_s"] = wall_s;
    j["achieved_speed"] = achieved_speed;
    j["contacts"] = tap_->counter("simulator", "robot_contacts") - contacts0;
    j["targets_reached"] = reached;
    j["targets_failed"] = failed;
    j["targets_timed_out"] = timed_out;
    j["reached_per_min"] = static_cast<double>(reached) / (sim_s / 60.0);
    j["longest_goal_s"] = longest_goal_s;
    // The planner measures waits on its own clock (wall time): in simulated seconds at the achieved speed.
    const int64_t wait_ms = tap_->counter("planner", "longest_wait_ms");
    j["longest_wait_s"] = wait_ms < 0 ? 0.0 : static_cast<double>(wait_ms) * 1e-3 * achieved_speed;
    j["deadlocks_broken"] = std::max<int64_t>(0, tap_->counter("planner", "deadlocks_broken"));
    return j;
  }

 private:
  // The map covers the whole world from the start: targets are never outside it.
  void start_processes(const sim::Bounds& bounds) {
    const std::string domain = std::to_string(lease_.id());
    const std::string broker = "tcp://127.0.0.1:" + std::to_string(group_.start_mosquitto());
    group_.start("gateway", {testkit::bin_path("slam-gateway"), "--domain", domain, "--broker", broker,
                             "--no-share", "--log-level", "warn"});
    group_.start("mapper",
                 {testkit::bin_path("slam-mapper"), "--domain", domain, "--store", group_.dir() + "/map.db",
                  "--grid-origin-x", fmt::format("{}", bounds.min.x - 1.0), "--grid-origin-y",
                  fmt::format("{}", bounds.min.y - 1.0), "--grid-width-m",
                  fmt::format("{}", bounds.max.x - bounds.min.x + 2.0), "--grid-height-m",
                  fmt::format("{}", bounds.max.y - bounds.min.y + 2.0), "--log-level", "warn"});
    // The planner's loop keeps its real-time pace in simulated time: 20 Hz times the speed.
    std::vector<std::string> planner = {
        o_.planner_bin.empty() ? testkit::bin_path("slam-planner") : o_.planner_bin,
        "--domain",
        domain,
        "--goal-store",
        "",
        "--no-share",
        "--planner-unknown",
        "allowed",
        "--coordination",
        o_.coordination,
        "--loop-rate-hz",
        fmt::format("{}", std::min(1000.0, 20.0 * o_.speed)),
        "--log-level",
        "warn"};
    planner.insert(planner.end(), o_.planner_args.begin(), o_.planner_args.end());
    group_.start("planner", planner);
    group_.start("simulator",
                 {testkit::bin_path("slam-simulator"), "--domain", domain, "--broker", broker, "--world",
                  o_.world, "--robots", std::to_string(o_.robots), "--speed", fmt::format("{}", o_.speed),
                  "--seed", std::to_string(o_.seed), "--log-level", "warn"});
  }

  void send_goal(const std::string& robot, uint64_t goal_id, Vec2 target) {
    NavGoal goal;
    goal.robot_id(robot);
    goal.goal_id(goal_id);
    goal.mode(GOAL_PLANNED);
    Point2 p;
    p.x(target.x);
    p.y(target.y);
    goal.target(p);
    tap_->goals().write(goal);
  }

  EvalOptions o_;
  std::mt19937_64 rng_;
  testkit::DomainLease lease_;
  testkit::ProcessGroup group_;
  std::unique_ptr<Tap> tap_;
  std::vector<Vec2> places_;
};

}  // namespace
}  // namespace slam::bench

int main(int argc, char** argv) {
  slam::bench::EvalOptions o;
  CLI::App app{"eval_coordination: robots sent to random places; contacts, waits and targets per minute"};
  app.add_option("--world", o.world, "built-in world: maze, office, ...")->capture_default_str();
  app.add_option("--robots", o.robots, "simulated robots")->capture_default_str();
  app.add_option("--speed", o.speed, "simulated seconds per wall-clock second")->capture_default_str();
  app.add_option("--duration", o.duration_s, "simulated seconds")->capture_default_str();
  app.add_option("--coordination", o.coordination, "the planner's --coordination")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  app.add_option("--seed", o.seed, "seed of the simulator and of the targets")->capture_default_str();
  app.add_option("--goal-timeout", o.goal_timeout_s, "simulated seconds after which a goal counts as stuck")
      ->capture_default_str();
  app.add_option("--planner-arg", o.planner_args, "extra planner argument (repeat)");
  app.add_option("--planner-bin", o.planner_bin, "the planner executable to run (default: this build's)");
  app.add_option("--out", o.out, "also write the JSON here");
  CLI11_PARSE(app, argc, argv);
  slam::bench::Evaluation eval(o);
  auto result = eval.run();
  if (!result) {
    std::fprintf(stderr, "eval_coordination: %s\n", result.message().c_str());
    return 1;
  }
  const std::string text = result->dump();
  std::printf("%s\n", text.c_str());
  if (!o.out.empty()) std::ofstream(o.out) << text << "\n";
  return 0;
}
