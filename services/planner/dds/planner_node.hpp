#pragma once
// slam-planner's DDS edge: reads grids, robot states, goals and path requests into a locked intake;
// one loop pass drains it into the core (PlanningGrid, Fleet), then writes waypoint commands and
// robot paths. Path requests go to RequestWorkers, which write their replies themselves.
// Several planners share the work: each reads every goal, but drives only the robots it owns and
// answers only the path requests it owns (Ownership over the planners' heartbeats); the other
// planners' RobotPaths tell it which frontiers their robots drive to and which goals they finished.
#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/core/counters.hpp"
#include "common/core/log.hpp"
#include "common/core/ownership.hpp"
#include "common/core/reply_cache.hpp"
#include "common/core/result.hpp"
#include "common/fastdds/fast_topics.hpp"
#include "planner/core/fleet.hpp"
#include "planner/core/fleet_coordinator.hpp"
#include "planner/core/goal_store.hpp"
#include "planner/core/planner_options.hpp"
#include "planner/dds/alert_node.hpp"
#include "planner/dds/mission_edge.hpp"
#include "planner/dds/planner_intake.hpp"
#include "planner/dds/planner_msgs.hpp"
#include "planner/dds/request_workers.hpp"

namespace slam::planner {

class PlannerNode {
 public:
  // Configure: participant, writers, request workers, readers. A failure undoes what was done.
  static Result<std::unique_ptr<PlannerNode>> create(const PlannerOptions& options, Counters& counters);
  PlannerNode(const PlannerNode&) = delete;
  PlannerNode& operator=(const PlannerNode&) = delete;

  dds::Participant& participant() { return *participant_; }

  // Faster than the 1 s default: a dead planner's robots move after options.peer_timeout_s.
  static constexpr std::chrono::milliseconds kHeartbeatPeriod{
      static_cast<std::int64_t>(kPlannerHeartbeatPeriodS * 1000.0)};

  // One loop pass: waits up to one loop period (less when a goal or request arrives), applies
  // what arrived, ticks the fleet, then writes robot paths and due waypoints.
  void run_once();

 private:
  // The heartbeat's view of the service.
  struct Metrics {
    explicit Metrics(Counters& c);
    std::atomic<int64_t>& path_requests;
    std::atomic<int64_t>& path_requests_repeated;  // retries answered from the cache or dropped
    std::array<std::atomic<int64_t>*, 7> replies;  // by PlanStatus
    std::atomic<int64_t>& goals_accepted;
    std::atomic<int64_t>& goals_rejected;
    std::atomic<int64_t>& goals_reached;
    std::atomic<int64_t>& goals_failed;
    std::atomic<int64_t>& goals_replayed;
    std::atomic<int64_t>& store_failures;
    std::atomic<int64_t>& replans;
    std::atomic<int64_t>& waypoints_sent;
    std::atomic<int64_t>& paths_published;
    std::atomic<int64_t>& robot_positions;
    std::atomic<int64_t>& robot_positions_rejected;
    std::atomic<int64_t>& snapshots;
    std::atomic<int64_t>& snapshots_rejected;
    std::atomic<int64_t>& patches_applied;
    std::atomic<int64_t>& patches_skipped;
    std::atomic<int64_t>&
        map_version;  // the grid version paths are planned on (the mapper's is ahead when lagging)
    std::atomic<int64_t>& write_failures;
    std::atomic<int64_t>& path_requests_not_owned;  // left to the planner that owns them
    std::atomic<int64_t>& robots_owned;
    std::atomic<int64_t>& planners_live;
    std::atomic<int64_t>& robots_held;  // told to wait or step aside by the coordinator
    std::atomic<int64_t>& deadlocks_broken;
    std::atomic<int64_t>& replans_around_robots;  // routes planned around a stopped robot
    std::atomic<int64_t>& longest_wait_ms;        // the longest wait of any robot so far
    std::atomic<int64_t>& revisits;               // exploring robots sent back to re-localise
  };

  PlannerNode(const PlannerOptions& options, Counters& counters);
  Status configure();

  void apply_grid(IntakeBatch& batch);
  void apply_positions(const std::vector<RobotPosition>& positions);
  void apply_uncertainties(const std::vector<RobotUncertainty>& uncertainties);
  // Logs and counts the exploring robots the fleet sent back to re-localise.
  void report_revisits();
  // Goals and homes from the store, before any reader runs: a restarted planner carries on.
  void resume_goals();
  void apply_goals(const std::vector<ReceivedGoal>& goals);
  // Records an accepted goal; a fleet goal also as each known robot's own goal (it replaced theirs).
  void store_goal(const std::string& robot_id, const Goal& goal, int64_t sent_ns);
  void flush_store();
  void report_waiting(const std::string& robot_id, const slam::NavGoal& sample);
  void reject_goal(const std::string& robot_id, const slam::NavGoal& sample, const std::string& reason);
  void submit_requests(const std::vector<slam::PathRequest>& requests);
  void count_replans();
  void publish_paths();
  // Traffic orders for every robot (FleetCoordinator), applied in stream_waypoints.
  void coordinate(int64_t now_ns);
  void stream_waypoints(int64_t now_ns);
  // Heartbeat reader thread.
  void on_heartbeat(const slam::Heartbeat& heartbeat);
  // RobotPath reader thread: keeps the latest report per robot for the loop.
  void on_path(const slam::RobotPath& sample);
  // Loop: drops silent planners, logs changes of the live set, hands the robots owned to the fleet
  // and the other planners' reports (claims, finished goals) to the fleet and the goal store.
  void update_ownership(int64_t now_mono_ns);
  void apply_reports();
  // The operator's ForgetRobot commands: fleet, goal store, paths and alerts drop each robot.
  void apply_forgets();
  // Runs on worker threads.
  void reply(const PathJob& job, const PlanResult& result);
  void warn(const std::string& key, const std::string& line);

  PlannerOptions options_;
  std::chrono::milliseconds period_;
  Metrics metrics_;
  Counters& counters_;  // the alerts add theirs
  std::atomic<int64_t>& robots_forgotten_;
  RateLimitedLog warnings_;

  // Loop state: touched by the loop thread only.
  PlanningGrid grid_;
  std::vector<CellBox> changed_tiles_;  // the patch being applied, reused
  Fleet fleet_;
  FleetCoordinator coordinator_;
  GoalStore goal_store_;
  bool awaiting_snapshot_ = false;
  uint64_t handed_revision_ = 0;  // grid revision the request workers have
  std::set<std::string> robots_;
  // The last command id sent to each robot (see stream_waypoints).
  std::map<std::string, uint64_t> waypoint_seq_;
  std::map<std::string, GoalStatus> reported_status_;
  IntakeBatch batch_;
  std::vector<DueWaypoint> due_;
  std::vector<Revisit> revisits_;
  slam::WaypointCommand command_;
  slam::RobotPath path_;
  uint64_t ownership_version_ = ~uint64_t{0};  // none logged yet
  std::vector<std::string> gone_;

  // Heartbeat reader thread, request intake in the loop and the loop.
  std::mutex ownership_mutex_;
  Ownership ownership_;

  // RobotPath reader thread writes, loop drains.
  std::mutex reports_mutex_;
  std::map<std::string, PathReport> reports_;
  std::map<std::string, PathReport> reports_taken_;

  // ForgetRobot reader thread writes, loop drains.
  std::mutex forget_mutex_;
  std::vector<std::string> forget_;
  std::vector<std::string> forget_taken_;

  PlannerIntake intake_;
  // Destroyed bottom-up: readers stop first, then the workers answer what is queued, then the
  // writers and the participant go.
  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<dds::Writer<slam::PathReply>> reply_writer_;
  ReplyCache<slam::PathReply> replies_sent_;  // written by the request workers, read by the loop
  std::unique_ptr<dds::Writer<slam::WaypointCommand>> waypoint_writer_;
  std::unique_ptr<dds::Writer<slam::RobotPath>> path_writer_;
  std::unique_ptr<RequestWorkers> workers_;
  std::unique_ptr<AlertNode> alerts_;  // the state reader feeds it, so it outlives the readers
  std::unique_ptr<dds::Reader<slam::GridSnapshot>> snapshot_reader_;
  std::unique_ptr<dds::Reader<slam::GridTiles>> patch_reader_;
  std::unique_ptr<dds::Reader<slam::RobotState>> state_reader_;
  std::unique_ptr<dds::Reader<slam::FleetDigest>> digest_reader_;
  std::unique_ptr<dds::Reader<slam::PoseCorrection>> correction_reader_;
  std::unique_ptr<dds::Reader<slam::NavGoal>> goal_reader_;
  std::unique_ptr<dds::Reader<slam::PathRequest>> request_reader_;
  std::unique_ptr<dds::Reader<slam::Heartbeat>> heartbeat_reader_;
  std::unique_ptr<dds::Reader<slam::RobotPath>> path_reader_;
  std::unique_ptr<dds::Reader<slam::ForgetRobot>> forget_reader_;
  // Its reader stops before the participant goes.
  MissionEdge missions_;
};

}  // namespace slam::planner
