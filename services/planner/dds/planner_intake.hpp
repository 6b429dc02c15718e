#pragma once
// What the DDS reader callbacks hand to the planner loop: copies of the samples behind one mutex.
// Callbacks only push (short, never blocking on planning); the loop waits here for work and takes
// everything in one go. Grid messages keep their order: a snapshot discards the patches queued
// before it, since it already contains them.
#include <slam/fastdds/correction.h>
#include <slam/fastdds/map.h>
#include <slam/fastdds/nav.h>
#include <slam/fastdds/robot.h>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "planner/core/robot_positions.hpp"

namespace slam::planner {

// A goal with its sender's timestamp (DDS source timestamp), which orders it against stored goals.
struct ReceivedGoal {
  slam::NavGoal sample;
  int64_t sent_ns = 0;
};

// A robot's position uncertainty from its pose correction (PoseCorrection.covariance).
struct RobotUncertainty {
  std::string robot_id;
  double sigma_m = 0.0;
};

struct IntakeBatch {
  std::optional<slam::GridSnapshot> snapshot;   // the latest one, applied before `patches`
  std::vector<slam::GridTiles> patches;         // in arrival order
  bool patches_dropped = false;                 // the queue overflowed: wait for the next snapshot
  std::vector<RobotPosition> positions;         // the newest per robot (RobotPositions)
  std::vector<RobotUncertainty> uncertainties;  // in arrival order
  std::vector<ReceivedGoal> goals;              // in arrival order
  std::vector<slam::PathRequest> requests;      // in arrival order

  void clear();
};

class PlannerIntake {
 public:
  // Patches beyond this between two loop passes mean the loop cannot keep up; they are dropped
  // and the grid waits for the next snapshot rather than growing memory without bound.
  static constexpr size_t kMaxQueuedPatches = 10000;

  void push_snapshot(const slam::GridSnapshot& sample);
  void push_patch(const slam::GridTiles& sample);
  // A robot's position from its state record or from a gateway's digest of every robot it hears:
  // the newest wins (RobotPositions).
  void push_state(const slam::RobotState& sample);
  void push_digest(const slam::FleetDigest& sample);
  // A robot's pose correction changed: its position uncertainty.
  void push_correction(const slam::PoseCorrection& sample);
  // The robot was forgotten: its next position is taken whatever its stamp.
  void forget_robot(const std::string& robot_id);
  void push_goal(const slam::NavGoal& sample, int64_t sent_ns);
  void push_request(const slam::PathRequest& sample);

  // Sleeps until `timeout` passes or a goal or path request arrives (they deserve an answer now).
  void wait(std::chrono::milliseconds timeout);
  // Moves everything queued into `out` (cleared first).
  void drain(IntakeBatch& out);

 private:
  std::mutex mutex_;
  std::condition_variable wake_;
  bool urgent_ = false;
  IntakeBatch pending_;
  RobotPositions positions_;
};

}  // namespace slam::planner
