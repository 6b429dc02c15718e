#pragma once
// The planner's missions on DDS: reads NavMission (senders' new missions and the other planners'
// progress) into a locked queue, and on each loop pass hands it to FleetMissions and writes the
// progress of the missions this planner drives. PlannerNode owns one and calls it from its loop.
#include <slam/fastdds/nav.h>

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "common/core/counters.hpp"
#include "common/core/log.hpp"
#include "common/core/result.hpp"
#include "common/fastdds/fast_topics.hpp"
#include "planner/core/fleet_missions.hpp"

namespace slam::planner {

// A NavMission as the core sees it: an error when a field cannot be represented (status out of range).
Result<ReceivedMission> to_mission(const slam::NavMission& sample, int64_t sent_ns);
void fill_mission(const std::string& robot_id, const Mission& mission, const MissionProgress& progress,
                  slam::NavMission& out);

class MissionEdge {
 public:
  explicit MissionEdge(Counters& counters);
  MissionEdge(const MissionEdge&) = delete;
  MissionEdge& operator=(const MissionEdge&) = delete;

  // Before connect(): the missions kept in the store start again.
  size_t resume(const GoalRecord& record, Fleet& fleet) { return missions_.resume(record, fleet); }
  // The writer, then the reader: from here on samples arrive.
  Status connect(dds::Participant& participant);
  // A goal was accepted for robot_id (or "*"): it cancels the missions it replaced.
  void goal_accepted(const std::string& robot_id) { missions_.goal_accepted(robot_id); }
  void forget(const std::string& robot_id) { missions_.forget(robot_id); }
  // One loop pass, after goals were applied: received missions, legs ended, progress written and kept.
  void run(Fleet& fleet, GoalStore& store);

 private:
  struct Received {
    slam::NavMission sample;
    int64_t sent_ns = 0;
  };
  void reject(const slam::NavMission& sample, const std::string& reason);
  void publish(const std::string& robot_id);

  std::atomic<int64_t>& accepted_;
  std::atomic<int64_t>& rejected_;
  std::atomic<int64_t>& replayed_;
  std::atomic<int64_t>& skipped_;
  std::atomic<int64_t>& published_;
  std::atomic<int64_t>& write_failures_;
  RateLimitedLog warnings_;

  FleetMissions missions_;
  std::vector<Received> taken_;
  std::vector<std::string> publish_;
  slam::NavMission out_;

  std::mutex mutex_;  // reader thread pushes, loop takes
  std::vector<Received> received_;

  // Destroyed reader first: its callback touches the queue above.
  std::unique_ptr<dds::Writer<slam::NavMission>> writer_;
  std::unique_ptr<dds::Reader<slam::NavMission>> reader_;
};

}  // namespace slam::planner
