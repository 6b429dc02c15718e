#pragma once
// Which waypoints the planner counted reached, read from the stream of a robot's RobotPath samples.
// Along one path the planner moves `current` past each waypoint it counts reached (status REACHED
// once past the last). An exploration leg is different: on arriving at its last waypoint the
// planner clears the path at once, so the published path goes from "current = k" to empty; the
// leg counts as reached when the robot's reported position (the planner's view) was within the
// planner's reach tolerance of every waypoint from k to the end, which is the planner's own rule.
// A path replaced or dropped before that counts nothing.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/core/geometry.hpp"

namespace slam::bench {

// The parts of a RobotPath sample this needs.
struct PathView {
  uint64_t goal_id = 0;
  std::vector<Vec2> waypoints;
  uint32_t current = 0;  // index of the waypoint being driven to; waypoints.size() once all are reached
};

class WaypointArrivals {
 public:
  // `reach_tolerance_m`: the planner's (--goals-reach-tolerance-m), plus any slack for the robot
  // moving between the planner's decision and the sample.
  explicit WaypointArrivals(double reach_tolerance_m) : tolerance_m_(reach_tolerance_m) {}

  // The waypoints counted reached between the robot's previous path sample and `now`, in order;
  // `reported` is the robot's latest map-frame position when known.
  std::vector<Vec2> update(const std::string& robot_id, const PathView& now, std::optional<Vec2> reported);

 private:
  double tolerance_m_;
  std::map<std::string, PathView> last_;
};

}  // namespace slam::bench
