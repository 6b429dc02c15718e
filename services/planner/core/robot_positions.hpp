#pragma once
// The newest position of each robot, from several sources: its RobotState (a status record, once
// a second or on a presence change) and the FleetDigest of every gateway that hears it (every
// robot, ten times a second). Which report is newest, and what a forget refuses, is LatestStamps'.
// Plain C++, single-threaded (the planner's intake calls it under its lock); buffers are reused.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "common/core/geometry.hpp"
#include "common/core/latest_stamps.hpp"

namespace slam::planner {

struct RobotPosition {
  std::string robot_id;
  Vec2 position;
  int64_t last_seen_ns = 0;
};

class RobotPositions {
 public:
  // Keeps `position` if it is the robot's newest report (LatestStamps). Returns whether it was kept.
  bool offer(std::string_view robot_id, Vec2 position, int64_t last_seen_ns);
  // Moves the newest position of each robot offered since the last take into `out` (replaced).
  void take(std::vector<RobotPosition>& out);
  // The robot was forgotten: a position offered since the last take goes, and so does any later
  // report that is not newer than its last one.
  void forget(std::string_view robot_id);

 private:
  struct Hash {
    using is_transparent = void;
    size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
  };
  struct Slot {
    uint64_t round = 0;  // the take() round its entry in pending_ belongs to
    size_t index = 0;    // in pending_, valid in that round only
  };
  LatestStamps stamps_;
  std::unordered_map<std::string, Slot, Hash, std::equal_to<>> slots_;
  std::vector<RobotPosition> pending_;
  uint64_t round_ = 1;
};

}  // namespace slam::planner
