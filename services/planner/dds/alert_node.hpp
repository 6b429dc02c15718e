#pragma once
// The alerts' DDS edge in the planner: robot states (handed over by the planner's state reader) and
// heartbeats (its own reader) go into an AlertMonitor, off the planner's loop; each loop pass publishes what
// changed on slam/system/alert and logs it, and a robot whose battery ran low is sent home with a NavGoal
// (mode home: where the planner first saw it), which every planner takes like an operator's goal.
// The planner hosts alerts because it already decides, with its peers, which one speaks for each
// robot: the owner of a robot raises its alerts, and service alerts go by the same rendezvous.
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include "common/core/counters.hpp"
#include "common/core/latest_stamps.hpp"
#include "common/core/request_retry.hpp"
#include "common/core/result.hpp"
#include "common/fastdds/fast_topics.hpp"
#include "planner/core/alert_monitor.hpp"

namespace slam::planner {

class AlertNode {
 public:
  // `self`: this planner's instance id (stamped on its alerts).
  static Result<std::unique_ptr<AlertNode>> create(dds::Participant& participant, const AlertConfig& config,
                                                   std::string self, Counters& counters);
  AlertNode(const AlertNode&) = delete;
  AlertNode& operator=(const AlertNode&) = delete;

  // Loop thread: publishes, logs and acts on what changed; `owns(key)` is the planners' ownership.
  void tick(int64_t now_mono_ns, const std::function<bool(const std::string&)>& owns);
  // The operator forgot the robot: its alerts clear at the next tick.
  void forget_robot(const std::string& robot_id);
  // A RobotState from the planner's reader (one reader feeds both: each sample is decoded once).
  // A record older than one already taken is ignored: a gateway that stopped hearing the robot
  // (its MQTT link lost) reports it offline while another gateway still hears it.
  void on_state(const slam::RobotState& state);
  // A PoseCorrection from the planner's reader: whether the mapper lost the robot.
  void on_correction(const slam::PoseCorrection& correction);

 private:
  AlertNode(const AlertConfig& config, std::string self, Counters& counters);
  void publish(const AlertChange& change);
  void send_home(const std::string& robot_id);

  // Facts change at human speed: the loop's 20 Hz would only repeat the same comparison.
  static constexpr int64_t kEvaluationPeriodNs = 250'000'000;

  std::string self_;
  int64_t next_evaluation_ns_ = 0;  // loop thread
  std::atomic<int64_t>& raised_;
  std::atomic<int64_t>& active_;
  std::atomic<int64_t>& sent_home_;
  std::atomic<int64_t>& write_failures_;
  RequestIdSource goal_ids_;
  slam::Alert sample_;

  std::mutex mutex_;  // reader threads and the loop
  AlertMonitor monitor_;
  LatestStamps record_stamps_;

  std::unique_ptr<dds::Writer<slam::Alert>> alert_writer_;
  std::unique_ptr<dds::Writer<slam::NavGoal>> goal_writer_;
  std::unique_ptr<dds::Reader<slam::Heartbeat>> heartbeat_reader_;
};

}  // namespace slam::planner
