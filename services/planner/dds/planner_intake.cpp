// PlannerIntake: the locked hand-over from reader callbacks to the planner loop.
#include "planner/dds/planner_intake.hpp"

#include <utility>

#include "common/core/geometry.hpp"

namespace slam::planner {

void IntakeBatch::clear() {
  snapshot.reset();
  patches.clear();
  patches_dropped = false;
  positions.clear();
  uncertainties.clear();
  goals.clear();
  requests.clear();
}

void PlannerIntake::push_snapshot(const slam::GridSnapshot& sample) {
  std::lock_guard lock(mutex_);
  pending_.snapshot = sample;
  pending_.patches.clear();
  pending_.patches_dropped = false;
}

void PlannerIntake::push_patch(const slam::GridTiles& sample) {
  std::lock_guard lock(mutex_);
  if (pending_.patches_dropped) return;
  if (pending_.patches.size() >= kMaxQueuedPatches) {
    pending_.patches.clear();
    pending_.patches_dropped = true;
    return;
  }
  pending_.patches.push_back(sample);
}

void PlannerIntake::push_state(const slam::RobotState& sample) {
  const auto& id = sample.robot_id();
  std::lock_guard lock(mutex_);
  positions_.offer({id.c_str(), id.size()}, {sample.pose().x(), sample.pose().y()}, sample.last_seen_ns());
}

void PlannerIntake::push_digest(const slam::FleetDigest& sample) {
  std::lock_guard lock(mutex_);
  for (const slam::DigestRobot& r : sample.robots()) {
    const auto& id = r.robot_id();
    positions_.offer({id.c_str(), id.size()}, {r.pose().x(), r.pose().y()}, r.last_seen_ns());
  }
}

void PlannerIntake::push_correction(const slam::PoseCorrection& sample) {
  const double sigma_m = position_sigma(sample.covariance());
  std::lock_guard lock(mutex_);
  pending_.uncertainties.push_back(RobotUncertainty{sample.robot_id().to_string(), sigma_m});
}

void PlannerIntake::forget_robot(const std::string& robot_id) {
  std::lock_guard lock(mutex_);
  positions_.forget(robot_id);
}

void PlannerIntake::push_goal(const slam::NavGoal& sample, int64_t sent_ns) {
  {
    std::lock_guard lock(mutex_);
    pending_.goals.push_back(ReceivedGoal{sample, sent_ns});
    urgent_ = true;
  }
  wake_.notify_one();
}

void PlannerIntake::push_request(const slam::PathRequest& sample) {
  {
    std::lock_guard lock(mutex_);
    pending_.requests.push_back(sample);
    urgent_ = true;
  }
  wake_.notify_one();
}

void PlannerIntake::wait(std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  wake_.wait_for(lock, timeout, [this] { return urgent_; });
}

void PlannerIntake::drain(IntakeBatch& out) {
  out.clear();
  std::lock_guard lock(mutex_);
  std::swap(out, pending_);
  positions_.take(out.positions);
  urgent_ = false;
}

}  // namespace slam::planner
