#pragma once
// Value types shared by every part of the planner core: plan results and path measures over the
// common geometry types; PlanStatus is the fleet's (common/core/fleet_messages.hpp).
#include <cstdint>
#include <string>
#include <vector>

#include "common/core/fleet_messages.hpp"
#include "common/core/geometry.hpp"

namespace slam::planner {

double path_length(const std::vector<Vec2>& path);
// Distance from p to the segment [a, b].
double distance_to_segment(Vec2 p, Vec2 a, Vec2 b);

using msg::PlanStatus;

// What to do with cells nobody has observed yet.
enum class UnknownPolicy : uint8_t {
  Blocked,  // never plan through unknown space
  Allowed   // plan through it, each step costing `unknown_cost_factor` times more
};

struct PlanResult {
  PlanStatus status = PlanStatus::NoMap;
  std::string reason;      // empty when status is Ok
  std::vector<Vec2> path;  // start .. goal in map coordinates, reduced to waypoints
  double length_m = 0.0;
  double planning_time_s = 0.0;

  bool ok() const { return status == PlanStatus::Ok; }
};

}  // namespace slam::planner
