// PlannerIntake: the locked hand-over from reader callbacks to the planner loop.
#include "planner/planner_intake.hpp"

#include <utility>

namespace slam::planner {

void IntakeBatch::clear() {
  snapshot.reset();
  patches.clear();
  patches_dropped = false;
  states.clear();
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
  std::lock_guard lock(mutex_);
  auto [it, inserted] = state_index_.try_emplace(sample.robot_id().to_string(), pending_.states.size());
  if (inserted) {
    pending_.states.push_back(sample);
  } else {
    pending_.states[it->second] = sample;
  }
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
  state_index_.clear();
  urgent_ = false;
}

}  // namespace slam::planner
