#pragma once
// Missions across the fleet: the MissionRunner joined to the Fleet's goal tracking and the
// GoalStore. Plain C++; the DDS edge (mission_edge.hpp) feeds it received missions and publishes
// what changed.
//
// How missions and goals relate: a mission replaces the robot's goal (it runs as a planned goal
// per waypoint); any goal accepted later for the robot, or for the whole fleet ("*", exploration
// included), cancels the mission. Which came last is decided by the senders' timestamps, as for
// goals (GoalStore::is_stale).
//
// Several planners share the robots as for goals: every planner follows every mission, but only
// the one owning the robot moves it on (a leg reached or failed); it publishes the progress, and
// the others adopt it, so the robot's next owner continues from the same waypoint. A restarted
// planner resumes from its store, then adopts what a live planner reports.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "common/core/result.hpp"
#include "planner/core/fleet.hpp"
#include "planner/core/goal_store.hpp"
#include "planner/core/mission_runner.hpp"

namespace slam::planner {

struct ReceivedMission {
  std::string robot_id;
  Mission mission;
  MissionProgress progress;
  int64_t sent_ns = 0;  // the sender's clock (DDS source timestamp)
};

class FleetMissions {
 public:
  enum class Receipt : uint8_t {
    Started,   // a new mission for the robot
    Adopted,   // progress of the running mission, from the planner driving the robot
    Ignored,   // an echo, a report on a mission not running here, or an ended one
    Replayed,  // not newer than the robot's goal or mission in the store
  };

  // The active missions kept in `record` start again where they were; returns how many.
  size_t resume(const GoalRecord& record, Fleet& fleet);
  // A received NavMission; an error when it is invalid (nothing changes then).
  Result<Receipt> receive(const ReceivedMission& received, Fleet& fleet, GoalStore& store);
  // A goal was accepted for robot_id (or "*"): the missions it replaced are cancelled.
  void goal_accepted(const std::string& robot_id);
  // The operator forgot the robot (ForgetRobot): its mission goes, unreported.
  void forget(const std::string& robot_id);
  // For robots owned here: a leg that ended (its tracker reached or failed it) starts the next one.
  // Returns the robots whose mission skipped a waypoint in this pass.
  std::vector<std::string> step(Fleet& fleet);
  // Robots whose mission changed since the last call, each kept in `store`; `publish` gets those
  // this planner reports (robots it owns, or not seen yet: then no planner drives them).
  void take_changed(const Fleet& fleet, GoalStore& store, std::vector<std::string>& publish);

  const MissionRunner& runner() const { return runner_; }

 private:
  MissionRunner runner_;
  std::map<std::string, int64_t> sent_ns_;  // per robot, of its mission's sender
};

}  // namespace slam::planner
