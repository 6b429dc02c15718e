// eval_traffic: the planner's fleet coordination without the processes. The simulator's own robot
// model (sim::Simulation: turning, collisions, the contact counter) drives on a built-in world; the
// planner's Fleet and FleetCoordinator plan, hold, yield and lead them on a grid of the true walls,
// each robot sent to one random reachable place after another, as eval_coordination does with the
// whole system. A 20-minute run of 10 robots takes some ten seconds, so a rule change can be judged over many
// seeds before the whole system measures it (the transport's delays and a map still being explored are left
// out).
// `--trace-wait S` prints every robot's order each time a wait passes a multiple of S seconds.
// Run: build/bin/eval_traffic --world maze --robots 10 --seeds 8
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "eval/world_places.hpp"
#include "planner/core/fleet.hpp"
#include "planner/core/fleet_coordinator.hpp"
#include "simulator/core/builtin_worlds.hpp"
#include "simulator/core/simulation.hpp"

namespace slam::bench {
namespace {

struct Options {
  std::string world = "maze";
  int robots = 10;
  double duration_s = 1200.0;  // simulated
  // Simulated seconds per planner second, as in eval_coordination: the planner's clock (its
  // waits and leader times) runs this much slower than the robots.
  double speed = 4.0;
  int seeds = 1;
  uint64_t first_seed = 1;
  double goal_timeout_s = 240.0;
  double min_trip_m = 2.0;
  double clearance_m = 0.35;
  bool clear_way = true;
  double trace_wait_s = 0.0;  // 0: no trace
};

constexpr double kMovedM = 0.005;  // a robot that moved less than this in a step stood

struct RunFigures {
  uint64_t contacts = 0, reached = 0, failed = 0, timed_out = 0;
  double longest_wait_s = 0.0;  // simulated
  // Robot-seconds: driving, held, stepping aside (arrived at the place or turning), standing with
  // nothing holding it, and standing pressed against a wall.
  double driving_s = 0.0, held_s = 0.0, aside_s = 0.0, standing_s = 0.0, at_wall_s = 0.0;
};

const char* order_name(planner::TrafficOrder o) {
  switch (o) {
    case planner::TrafficOrder::Go:
      return "go";
    case planner::TrafficOrder::Wait:
      return "wait";
    case planner::TrafficOrder::Yield:
      return "yield";
  }
  return "?";
}

struct Run {
  uint64_t goal_id = 0;
  double sent_s = 0.0;    // simulated
  double traced_s = 0.0;  // the wait last traced
};

// Every robot's order, each time a robot's wait passes another multiple of --trace-wait.
void trace(const Options& o, const sim::Simulation& simulation, const planner::FleetCoordinator& coordinator,
           int64_t now_ns, std::map<std::string, Run>& runs) {
  for (const sim::Robot& r : simulation.robots()) {
    Run& run = runs[r.id];
    const double waited = coordinator.wait_s(r.id, now_ns) * o.speed;
    if (waited <= 0.0) run.traced_s = 0.0;
    if (waited <= 0.0 || waited < run.traced_s + o.trace_wait_s) continue;
    run.traced_s = waited;
    std::printf("t=%.0f s: %s held %.0f s; leader %s\n", simulation.time(), r.id.c_str(), waited,
                coordinator.leader().c_str());
    for (const sim::Robot& k : simulation.robots()) {
      const auto h = coordinator.hold_of(k.id);
      std::printf("  %s at (%.2f, %.2f): %s to (%.2f, %.2f)%s%s%s%s, held %.0f s\n", k.id.c_str(),
                  k.true_pose.x, k.true_pose.y, order_name(h.order), h.hold.x, h.hold.y,
                  h.blocker.empty() ? "" : " for ", h.blocker.c_str(), h.deadlock ? " (deadlock)" : "",
                  h.section ? " (section)" : "", coordinator.wait_s(k.id, now_ns) * o.speed);
    }
  }
}

Result<RunFigures> run_one(const Options& o, uint64_t seed) {
  auto world = sim::builtin_world(o.world);
  if (!world) return world.error();
  const planner::PlanningGrid grid = planning_grid_of(*world, 0.05, 0.2);
  sim::SimulationConfig sc;
  sc.seed = seed;
  sc.odometry.drift_per_metre = 0.0;
  sc.odometry.drift_per_radian = 0.0;
  auto made = sim::Simulation::create(*world, sc);
  if (!made) return made.error();
  sim::Simulation simulation = std::move(*made);
  auto ids = simulation.spawn_random(static_cast<size_t>(o.robots));
  if (!ids) return ids.error();
  const auto places =
      reachable_places(*world, simulation.robots().front().true_pose.position(), o.clearance_m);
  if (places.empty()) return Error{"no reachable place in world " + o.world};

  planner::FleetConfig fc;
  planner::Fleet fleet(fc);
  planner::CoordinationConfig cc;
  cc.clear_way = o.clear_way;
  planner::FleetCoordinator coordinator(cc);
  fleet.grid_changed(grid, std::nullopt);

  std::mt19937_64 rng(seed);
  std::map<std::string, Run> runs;
  uint64_t next_goal = 1000;
  RunFigures f;
  std::vector<planner::DueWaypoint> due;
  std::vector<Vec2> before(simulation.robots().size());
  const auto steps = static_cast<int64_t>(o.duration_s / sc.dt);
  for (int64_t step = 0; step < steps; ++step) {
    const double sim_s = simulation.time();
    const auto now_ns = static_cast<int64_t>(sim_s / o.speed * 1e9);
    for (const sim::Robot& r : simulation.robots()) {
      const Vec2 at = r.true_pose.position();
      fleet.observe(r.id, at);
      coordinator.observe(r.id, at);
      Run& run = runs[r.id];
      const planner::GoalTracker* t = fleet.tracker(r.id);
      bool next = run.goal_id == 0;
      if (!next && t != nullptr && t->goal().goal_id == run.goal_id) {
        if (t->status() == planner::GoalStatus::Reached) {
          ++f.reached;
          next = true;
        } else if (t->status() == planner::GoalStatus::Failed) {
          ++f.failed;
          next = true;
        }
      }
      if (!next && sim_s - run.sent_s > o.goal_timeout_s) {
        ++f.timed_out;
        next = true;
      }
      if (!next) continue;
      const Vec2 target = pick_place(places, at, o.min_trip_m, rng);
      run.goal_id = ++next_goal;
      run.sent_s = sim_s;
      if (auto started = fleet.set_goal(r.id, planner::Goal{run.goal_id, planner::GoalMode::Planned, target});
          !started)
        return started.error();
    }
    fleet.tick(grid, now_ns);
    coordinator.coordinate(fleet, grid, now_ns);
    fleet.due_waypoints(now_ns, due);
    coordinator.dispatch(fleet, due);
    for (const planner::DueWaypoint& d : due) SLAM_TRY(simulation.set_waypoint(d.robot_id, d.waypoint));
    for (size_t k = 0; k < simulation.robots().size(); ++k)
      before[k] = simulation.robots()[k].true_pose.position();
    simulation.step();
    // Where the robots' time goes: driving, or standing (held, stepping aside, or with nothing
    // holding it: turning on the spot, or pressed against a wall).
    for (size_t k = 0; k < simulation.robots().size(); ++k) {
      const sim::Robot& r = simulation.robots()[k];
      const bool moved = distance(before[k], r.true_pose.position()) > kMovedM;
      const planner::TrafficOrder order = coordinator.order(r.id);
      double& share = moved                                   ? f.driving_s
                      : order == planner::TrafficOrder::Wait  ? f.held_s
                      : order == planner::TrafficOrder::Yield ? f.aside_s
                      : simulation.world().is_free(r.true_pose.position(), sc.robot.radius + kMovedM)
                          ? f.standing_s
                          : f.at_wall_s;
      share += sc.dt;
    }

    const double wait_s = coordinator.longest_wait_s(now_ns) * o.speed;
    f.longest_wait_s = std::max(f.longest_wait_s, wait_s);
    if (o.trace_wait_s > 0.0) trace(o, simulation, coordinator, now_ns, runs);
  }
  f.contacts = simulation.contacts();
  return f;
}

}  // namespace
}  // namespace slam::bench

int main(int argc, char** argv) {
  slam::bench::Options o;
  CLI::App app{"eval_traffic: the planner's fleet coordination on a built-in world, without the processes"};
  app.add_option("--world", o.world, "built-in world: maze, office, ...")->capture_default_str();
  app.add_option("--robots", o.robots, "simulated robots")->capture_default_str();
  app.add_option("--duration", o.duration_s, "simulated seconds per run")->capture_default_str();
  app.add_option("--speed", o.speed, "simulated seconds per planner second (eval_coordination's --speed)")
      ->capture_default_str();
  app.add_option("--seeds", o.seeds, "runs, with seeds first-seed, first-seed + 1, ...")
      ->capture_default_str();
  app.add_option("--first-seed", o.first_seed, "seed of the first run")->capture_default_str();
  app.add_option("--goal-timeout", o.goal_timeout_s, "simulated seconds after which a goal counts as stuck")
      ->capture_default_str();
  app.add_option("--clear-way", o.clear_way, "the leader rule (the planner's --coordination-clear-way)")
      ->capture_default_str();
  app.add_option("--trace-wait", o.trace_wait_s,
                 "print every robot's order each time a wait passes a multiple")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  std::printf(
      "seed contacts reached failed timed_out per_min longest_wait_s | robot time %%: driving held aside "
      "standing at_wall\n");
  for (int k = 0; k < o.seeds; ++k) {
    const uint64_t seed = o.first_seed + static_cast<uint64_t>(k);
    const auto f = slam::bench::run_one(o, seed);
    if (!f) {
      std::fprintf(stderr, "eval_traffic: seed %llu: %s\n", static_cast<unsigned long long>(seed),
                   f.message().c_str());
      return 1;
    }
    const double all = f->driving_s + f->held_s + f->aside_s + f->standing_s + f->at_wall_s;
    const auto pct = [&](double v) { return all > 0.0 ? 100.0 * v / all : 0.0; };
    std::printf("%llu %llu %llu %llu %llu %.2f %.0f | %.0f %.0f %.0f %.0f %.1f\n",
                static_cast<unsigned long long>(seed), static_cast<unsigned long long>(f->contacts),
                static_cast<unsigned long long>(f->reached), static_cast<unsigned long long>(f->failed),
                static_cast<unsigned long long>(f->timed_out),
                static_cast<double>(f->reached) / (o.duration_s / 60.0), f->longest_wait_s, pct(f->driving_s),
                pct(f->held_s), pct(f->aside_s), pct(f->standing_s), pct(f->at_wall_s));
    std::fflush(stdout);
  }
  return 0;
}
