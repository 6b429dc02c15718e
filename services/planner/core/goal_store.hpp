#pragma once
// The goals the planner was given, kept in a file so that a restarted planner resumes them. DDS
// alone does not do it: a goal lives only in its writer's transient-local cache, and a short-lived
// sender (slamctl) is gone when the planner restarts. Homes are kept too, so that "home" still
// means where a robot was first seen. Goals change at human speed: changes are collected and the
// whole file is rewritten by flush() (temporary file + rename: a crash leaves the old file or the
// new one, never half of one). Missions are kept alike, with their progress, so that a restarted
// planner carries on from the waypoint the robot was driving to.
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "common/core/result.hpp"
#include "planner/core/goal_tracker.hpp"
#include "planner/core/mission_runner.hpp"

namespace slam::planner {

struct StoredGoal {
  std::string robot_id;  // one robot or kAllRobots
  Goal goal;
  int64_t sent_ns = 0;    // the sender's clock: orders goals across a restart and spots replays
  bool finished = false;  // reached or failed: kept to spot replays, not resumed
};

struct StoredMission {
  std::string robot_id;
  Mission mission;
  MissionProgress progress;  // resumed while Active
  int64_t sent_ns = 0;       // as StoredGoal's
};

struct GoalRecord {
  std::map<std::string, StoredGoal> goals;        // the latest goal per robot_id
  std::map<std::string, StoredMission> missions;  // the latest mission per robot_id
  std::map<std::string, Vec2> homes;              // where each robot was first seen
};

// The file's text (JSON, documented in docs/services.md) to a record, or what is wrong with it.
Result<GoalRecord> parse_goal_record(std::string_view text);
std::string format_goal_record(const GoalRecord& record);

// The goals to resume, oldest first; a fleet goal ("*") before robot goals sent at the same time
// (a fleet goal is recorded with the robot goals it started, which must win over it).
std::vector<StoredGoal> goals_to_resume(const GoalRecord& record);

// The missions to resume (still active), oldest first.
std::vector<StoredMission> missions_to_resume(const GoalRecord& record);

class GoalStore {
 public:
  // Reads `path`; a missing file is an empty store. An empty path keeps goals in memory only.
  static Result<GoalStore> open(const std::string& path);

  const GoalRecord& record() const { return record_; }
  const std::string& path() const { return path_; }

  // True when a goal or mission for robot_id sent at sent_ns is not newer than the goal or mission
  // kept: a replay from a DDS cache after a restart, or an older one arriving late.
  bool is_stale(const std::string& robot_id, int64_t sent_ns) const;
  // Keeps `goal` as its robot's current goal; it cancels the robot's mission (every mission for a
  // fleet goal).
  void put(const StoredGoal& goal);
  // Keeps a robot's mission, new or moved on; a new one finishes the robot's goal (it replaced it).
  void put_mission(const StoredMission& mission);
  // Marks robot_id's goal finished if it is still goal_id; the fleet-wide goal with that id too
  // once every robot that took it has finished it.
  void finish(const std::string& robot_id, uint64_t goal_id);
  // The operator forgot the robot: its goal and home are dropped.
  void forget(const std::string& robot_id);
  // Keeps a robot's home unless one is kept already.
  void put_home(const std::string& robot_id, Vec2 home);

  bool dirty() const { return dirty_; }
  // Writes the file when something changed since the last flush.
  Status flush();

 private:
  std::string path_;
  GoalRecord record_;
  bool dirty_ = false;
};

}  // namespace slam::planner
