#pragma once
// A small kinematic run of the traffic rules for the unit tests: robots drive to their next
// waypoint, or to where they are told to hold, at a fixed speed; the run records the closest two
// robots came, whether all arrived, and the longest wait.
#include <algorithm>
#include <cstddef>
#include <functional>
#include <limits>
#include <vector>

#include "planner/core/fleet_coordinator.hpp"

namespace slam::planner::test {

constexpr double kDt = 0.05;      // s
constexpr double kSpeed = 0.5;    // m/s
constexpr double kArrive = 0.05;  // m

struct Bot {
  Vec2 position;
  std::vector<Vec2> path;  // waypoints; the last one is the destination
  int64_t since_ns = 0;
  size_t next = 0;
  // Drives back the way it stepped aside before going on (the straight line to the next waypoint
  // may cross a wall once it has left its path).
  bool retrace = false;
  Vec2 last_hold{-1.0, -1.0};
  bool arrived() const { return next >= path.size(); }
};

struct RunResult {
  double closest = std::numeric_limits<double>::infinity();  // smallest distance between two robots
  bool all_arrived = false;
  uint64_t deadlocks = 0;
  size_t yields = 0;  // robot-steps spent yielding
  double longest_wait_s = 0.0;
};

inline std::vector<TrafficRobot> inputs(const std::vector<Bot>& bots) {
  std::vector<TrafficRobot> out;
  for (size_t i = 0; i < bots.size(); ++i) {
    const Bot& b = bots[i];
    const std::span<const Vec2> all(b.path);
    out.push_back(TrafficRobot{b.position, all.subspan(std::min(b.next, b.path.size())), b.since_ns,
                               static_cast<uint32_t>(i)});
  }
  return out;
}

// `each_step` (if given) sees the robots after every step.
inline RunResult run(const PlanningGrid& grid, std::vector<Bot>& bots, const CoordinationConfig& config,
                     int steps, const std::function<void(const std::vector<Bot>&)>& each_step = {}) {
  TrafficRules rules(config);
  std::vector<TrafficDecision> decisions;
  RunResult result;
  for (int step = 0; step < steps; ++step) {
    const auto now = static_cast<int64_t>(step) * 50'000'000;
    const auto in = inputs(bots);
    rules.decide(grid, in, now, decisions);
    for (size_t i = 0; i < bots.size(); ++i) {
      Bot& b = bots[i];
      const TrafficDecision& d = decisions[i];
      if (d.order == TrafficOrder::Yield) ++result.yields;
      if (d.waiting_since_ns >= 0)
        result.longest_wait_s =
            std::max(result.longest_wait_s, static_cast<double>(now - d.waiting_since_ns) * 1e-9);
      if (b.retrace && d.order == TrafficOrder::Yield && distance(d.hold, b.last_hold) > 1e-9 &&
          distance(d.hold, b.position) > 1e-9) {
        b.path.insert(b.path.begin() + static_cast<std::ptrdiff_t>(b.next), b.position);
        b.last_hold = d.hold;
      }
      if (d.order == TrafficOrder::Go && b.arrived()) continue;
      const Vec2 target = d.order == TrafficOrder::Go ? b.path[b.next] : d.hold;
      const double gap = distance(b.position, target);
      b.position = gap <= kSpeed * kDt ? target : b.position + (target - b.position) * (kSpeed * kDt / gap);
      if (d.order == TrafficOrder::Go && distance(b.position, b.path[b.next]) < kArrive) ++b.next;
    }
    if (each_step) each_step(bots);
    for (size_t i = 0; i < bots.size(); ++i)
      for (size_t j = i + 1; j < bots.size(); ++j)
        result.closest = std::min(result.closest, distance(bots[i].position, bots[j].position));
    if (std::all_of(bots.begin(), bots.end(), [](const Bot& b) { return b.arrived(); })) {
      result.all_arrived = true;
      break;
    }
  }
  result.deadlocks = rules.deadlocks();
  return result;
}

}  // namespace slam::planner::test
