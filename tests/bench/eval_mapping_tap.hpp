#pragma once
// What an eval_mapping run hears on DDS while it runs, and the requests it sends: ground truth,
// digests, corrections and paths go to the RunRecorder; the world, the services' counters, each
// robot's latest goal status and the mapper's replies are kept for the run to ask.
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/core/result.hpp"
#include "common/fastdds/fast_topics.hpp"
#include "eval/run_recorder.hpp"
#include "simulator/core/geometry.hpp"

namespace slam::bench {

class SystemTap {
 public:
  static Result<std::unique_ptr<SystemTap>> create(int domain, RunRecorder& recorder);

  // A counter of the latest Heartbeat of `service`; -1 when none was heard.
  int64_t counter(const std::string& service, const std::string& name) const;
  // The latest Heartbeat's counters of `service` whose names start with `prefix`.
  std::map<std::string, int64_t> counters(const std::string& service, const std::string& prefix) const;
  std::optional<SimWorld> world() const;
  // Whether `robots` robots have ended goal `goal_id` (reached or failed), by their RobotPath.
  bool goal_ended(uint64_t goal_id, size_t robots) const;
  std::optional<MapReply> reply(uint64_t id) const;
  dds::Writer<NavGoal>& goals() { return *goals_; }
  dds::Writer<MapFileRequest>& files() { return *files_; }
  dds::Writer<NavMission>& missions() { return *missions_; }

 private:
  explicit SystemTap(RunRecorder& recorder) : recorder_(recorder) {}
  Status connect(int domain);

  RunRecorder& recorder_;
  // Written by the listeners: declared before the readers so it outlives them (members are
  // destroyed in reverse order).
  mutable std::mutex mutex_;
  std::optional<SimWorld> world_;
  std::map<std::string, std::map<std::string, int64_t>> counters_;
  std::map<uint64_t, MapReply> replies_;
  std::map<std::string, std::pair<uint64_t, GoalStatus>> goal_status_;  // latest RobotPath per robot
  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<dds::Reader<SimGroundTruth>> truth_;
  std::unique_ptr<dds::Reader<FleetDigest>> digests_;
  std::unique_ptr<dds::Reader<PoseCorrection>> corrections_;
  std::unique_ptr<dds::Reader<RobotPath>> paths_;
  std::unique_ptr<dds::Reader<SimWorld>> worlds_;
  std::unique_ptr<dds::Reader<Heartbeat>> heartbeats_;
  std::unique_ptr<dds::Reader<MapReply>> replies_reader_;
  std::unique_ptr<dds::Writer<NavGoal>> goals_;
  std::unique_ptr<dds::Writer<MapFileRequest>> files_;
  std::unique_ptr<dds::Writer<NavMission>> missions_;
};

// The simulator's walls, as the map metrics take them.
std::vector<sim::Segment> walls_of(const SimWorld& world);

}  // namespace slam::bench
