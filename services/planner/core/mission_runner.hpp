#pragma once
// Missions: a robot's list of waypoints, driven in order once or looped (patrol), layered above the
// per-robot goal tracking. Each waypoint is one leg: a planned goal to it, with the mission's id as
// goal id. The runner says which leg comes next when one ends; what happens on the robot is the
// GoalTracker's business. Pure logic, no DDS: the service feeds it leg outcomes.
//
// An unreachable waypoint (its leg failed) is reported in the progress and skipped; the mission
// fails when every waypoint failed in a row, or when a whole pass of a looped mission reached fewer
// than two waypoints (the robot could not move: legs would end at once, lap after lap). So a patrol
// survives one blocked door but does not spin when it cannot go anywhere.
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/core/result.hpp"
#include "planner/core/goal_tracker.hpp"

namespace slam::planner {

using msg::MissionStatus;

inline constexpr size_t kMaxMissionWaypoints = 256;  // NavMission.waypoints' bound

struct Mission {
  uint64_t mission_id = 0;
  std::vector<Vec2> waypoints;
  bool loop = false;
};

struct MissionProgress {
  size_t current = 0;  // the waypoint being driven to
  uint32_t laps = 0;   // passes completed
  MissionStatus status = MissionStatus::Active;
  std::string reason;  // the last skipped waypoint and why, or why the mission failed

  bool operator==(const MissionProgress&) const = default;
};

// Ok, or what is wrong: no waypoint, too many, a non-finite one, a loop of one waypoint, a current
// index past the end.
Status validate(const Mission& mission, const MissionProgress& progress = {});

// The leg towards waypoints[current].
Goal leg_goal(const Mission& mission, const MissionProgress& progress);

class MissionRunner {
 public:
  struct Running {
    Mission mission;
    MissionProgress progress;
    size_t failures_in_row = 0;  // legs failed since the last one reached
    size_t legs_in_pass = 0;     // legs ended since the pass began at waypoint 0
    size_t reached_in_pass = 0;  // of those, reached
  };

  // Starts robot_id's mission at `progress` (a resumed or adopted mission continues where it was);
  // it replaces any running one. Returns the leg goal to give the robot. The mission must be valid.
  Goal start(const std::string& robot_id, const Mission& mission, const MissionProgress& progress = {});
  // A goal replaced the robot's mission: it is cancelled. False when none was running.
  bool cancel(const std::string& robot_id);
  // Cancels every running mission (a goal for the whole fleet); returns the robots that had one.
  std::vector<std::string> cancel_all();
  // The operator forgot the robot: its mission is dropped without a report.
  void forget(const std::string& robot_id);
  // The current leg ended: reached, or failed with `reason`. Returns the next leg's goal, or nullopt
  // when the mission is over (done or failed).
  std::optional<Goal> leg_ended(const std::string& robot_id, bool reached, const std::string& reason);
  // Another planner drives the robot and reported its progress on the same mission: taken over as
  // is. Returns the leg goal when the current waypoint changed and the mission still runs.
  std::optional<Goal> adopt(const std::string& robot_id, const MissionProgress& progress);

  // The robot's mission: running, or the last one ended (until another starts).
  const Running* find(const std::string& robot_id) const;
  bool active(const std::string& robot_id) const;
  const std::map<std::string, Running>& missions() const { return missions_; }
  // Robots whose mission started, moved on or ended since the last call.
  std::vector<std::string> take_changed();

 private:
  void end(Running& r, MissionStatus status, const std::string& reason);

  std::map<std::string, Running> missions_;
  std::set<std::string> changed_;
};

}  // namespace slam::planner
