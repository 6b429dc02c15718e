#pragma once
// What an evaluation run keeps from the system while it runs, fed from DDS callbacks (any thread)
// as plain values: every ground-truth sample pairs each robot's true pose with its raw odometry,
// with the server's corrected pose (the mapper's latest map <- odom correction applied to that
// same odometry, so no transport delay enters the error) and with the latest published pose (the
// FleetDigest the planner follows); waypoints the planner counts reached are paired with the next
// truth sample of that robot; every change of a robot's correction is kept with the robot's latest
// truth sample (closure_audit.hpp).
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "eval/closure_audit.hpp"
#include "eval/trajectory_metrics.hpp"
#include "eval/waypoint_arrivals.hpp"

namespace slam::bench {

struct RobotTruth {
  std::string robot_id;
  Pose true_pose;
  Pose reported_pose;  // the robot's odometry, in its own frame
};

// One sampled truth instant of one robot, with its stamp (the clock of the robots' observations):
// what an offline replay of the run's stored observations is scored against (truth_log.hpp).
struct TruthSample {
  int64_t stamp_ns = 0;
  RobotTruth truth;
};

// A waypoint counted reached: where it was, and how far from it the robot truly and reportedly was.
struct GoalArrival {
  std::string robot_id;
  Vec2 waypoint;
  double true_distance_m = 0.0;
  double reported_distance_m = 0.0;
};

// A robot's first placement on the map (a correction published as placed), with its truth then.
struct RobotPlacement {
  std::string robot_id;
  double after_s = 0.0;  // since its first truth sample, on the observations' clock
  double error_m = 0.0;  // the placed correction applied to its odometry, against where it truly was
};

class RunRecorder {
 public:
  // `sample_period_ns`: wall time between trajectory samples (one simulated second at the run's
  // speed); `reach_tolerance_m` as WaypointArrivals.
  RunRecorder(int64_t sample_period_ns, double reach_tolerance_m);

  // Sampling runs between start() and stop(); the other inputs are kept all the time.
  void start();
  void stop();

  void on_truth(int64_t stamp_ns, const std::vector<RobotTruth>& robots);
  void on_published_pose(const std::string& robot_id, Vec2 map_position);
  // `loop`: the change comes from a loop closure (CORRECTION_LOOP); `placed`: the robot's place on
  // the map is known (PLACEMENT_PLACED), not searched for.
  void on_correction(const std::string& robot_id, const Pose& map_from_odom, uint64_t version, bool loop,
                     bool placed = true);
  void on_path(const std::string& robot_id, const PathView& path);

  std::vector<TrajectorySample> samples() const;
  // The truth of every sampled instant (the instants samples() holds), in order.
  std::vector<TruthSample> truth_samples() const;
  // Latest published position (FleetDigest) beside the truth, per sample where one was known.
  std::vector<std::pair<Vec2, Vec2>> published_vs_truth() const;
  std::vector<GoalArrival> arrivals() const;
  // First true position of every robot seen (flood-fill starts) and each robot's true track.
  std::vector<Vec2> true_starts() const;
  std::map<std::string, std::vector<Vec2>> true_tracks() const;
  size_t robots_seen() const;
  size_t robots_published() const;
  size_t corrected_robots() const;  // robots with a correction of version > 0
  // Changes whose previous correction and truth were known; the others are only counted: before
  // the robot's first truth sample, or when the first version heard is not 1 (what it replaced is
  // unknown), or when the version did not grow (a repeat, or a sequence that started again).
  std::vector<CorrectionChange> correction_changes() const;
  // Each robot's first placement, in the order they happened; robots never placed are missing.
  std::vector<RobotPlacement> placements() const;
  // The samples of robots already placed (what a robot searched for publishes is no estimate).
  std::vector<TrajectorySample> placed_samples() const;
  size_t unscored_corrections() const;

 private:
  struct Robot {
    std::optional<RobotTruth> truth;
    int64_t truth_stamp_ns = 0;
    int64_t first_truth_stamp_ns = 0;
    bool placed = false;
    std::optional<Vec2> state;
    Pose correction;
    uint64_t correction_version = 0;
    std::vector<Vec2> track;
    std::vector<GoalArrival> pending;  // waiting for the next truth sample
  };

  mutable std::mutex mutex_;
  int64_t sample_period_ns_;
  WaypointArrivals waypoint_arrivals_;
  bool sampling_ = false;
  int64_t next_sample_ns_ = -1;
  std::map<std::string, Robot> robots_;
  std::vector<Vec2> starts_;
  std::vector<TrajectorySample> samples_;
  std::vector<TrajectorySample> placed_samples_;
  std::vector<RobotPlacement> placements_;
  std::vector<TruthSample> truth_samples_;
  std::vector<std::pair<Vec2, Vec2>> published_;
  std::vector<GoalArrival> arrivals_;
  std::vector<CorrectionChange> changes_;
  size_t unscored_corrections_ = 0;
};

}  // namespace slam::bench
