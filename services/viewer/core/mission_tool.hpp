#pragma once
// The mission tool (Drive tab): while armed, a left click on the map appends a waypoint to a draft
// mission instead of doing the click's action; Send gives the draft to the selected robot, driven
// once or looped; Undo drops the last waypoint, Clear all of them. The draft stays after sending, so
// a patrol can be adjusted and sent again.
#include <cstddef>
#include <string>
#include <vector>

#include "common/core/result.hpp"
#include "viewer/core/commands.hpp"

namespace slam::viewer {

inline constexpr size_t kMaxMissionWaypoints = 256;  // NavMission.waypoints' bound

class MissionTool {
 public:
  bool armed() const { return armed_; }
  void set_armed(bool armed) { armed_ = armed; }
  bool loop() const { return loop_; }
  void set_loop(bool loop) { loop_ = loop; }
  const std::vector<Vec2>& waypoints() const { return waypoints_; }

  // Appends a map-frame waypoint; an error (nothing added) when the draft is full.
  Status add(Vec2 world);
  void undo();
  void clear() { waypoints_.clear(); }
  // The draft as a mission for `robot_id`, or why it cannot be sent (every robot, no waypoint, a
  // loop of one waypoint).
  Result<MissionCommand> command(const std::string& robot_id) const;

 private:
  bool armed_ = false;
  bool loop_ = false;
  std::vector<Vec2> waypoints_;
};

}  // namespace slam::viewer
