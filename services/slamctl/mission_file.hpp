#pragma once
// What `slamctl mission` sends: waypoints from the command line (x1 y1 x2 y2 ...) or from a mission
// file, and the line `slamctl missions` prints per robot. Plain C++ over the generated value types.
//
// A mission file is YAML (docs/services.md):
//   loop: true            # optional, default false; --loop on the command line also loops
//   waypoints:            # [x, y] in metres, map frame, driven in this order
//     - [1.0, 2.0]
//     - [4.5, 2.0]
#include <string>
#include <string_view>
#include <vector>

#include "common/core/result.hpp"
#include "common/fastdds/fast_topics.hpp"

namespace slam::ctl {

struct MissionSpec {
  std::vector<Point2> waypoints;
  bool loop = false;
};

// x1 y1 x2 y2 ...: pairs of finite numbers, at least one pair.
Result<std::vector<Point2>> waypoints_from_numbers(const std::vector<double>& xy);
// A mission file's text; errors name the entry at fault.
Result<MissionSpec> parse_mission_file(std::string_view yaml);
Result<MissionSpec> load_mission_file(const std::string& path);

// True when `next` is an earlier state of the mission `kept` shows: its sender and the planner
// reporting progress both keep a robot's mission, and a late reader gets them in any order.
bool mission_behind(const NavMission& next, const NavMission& kept);

// "ROBOT mission M: active, waypoint 2/4 (1.00, 2.00), 3 lap(s) done, looped": one robot's mission.
std::string format_mission(const NavMission& mission);

}  // namespace slam::ctl
