// MapperIntake: the locked hand-over between DDS listener threads and the map loop.
#include "mapper/dds/mapper_intake.hpp"

#include <utility>

namespace slam::mapper {

void MapperBatch::clear() {
  observations.clear();
  commands.clear();
  initial_poses.clear();
  placement_answers.clear();
  dropped = 0;
}

void MapperIntake::push(const slam::RobotObservationBatch& batch) {
  std::lock_guard lock(mutex_);
  for (const slam::RobotObservation& o : batch.observations()) {
    if (pending_.observations.size() >= max_observations_) {
      ++pending_.dropped;
      continue;
    }
    pending_.observations.push_back(o);
  }
}

void MapperIntake::push(MapCommand command) {
  push_urgent(pending_.commands, std::move(command));
}

void MapperIntake::push(const slam::InitialPose& request) {
  push_urgent(pending_.initial_poses, request);
}

void MapperIntake::push(const slam::PlacementAnswer& request) {
  push_urgent(pending_.placement_answers, request);
}

void MapperIntake::notify() {
  {
    std::lock_guard lock(mutex_);
    urgent_ = true;
  }
  wake_.notify_one();
}

void MapperIntake::wait_until(std::chrono::steady_clock::time_point deadline) {
  std::unique_lock lock(mutex_);
  wake_.wait_until(lock, deadline, [this] { return urgent_; });
  urgent_ = false;
}

void MapperIntake::drain(MapperBatch& out) {
  out.clear();
  std::lock_guard lock(mutex_);
  std::swap(out, pending_);
}

}  // namespace slam::mapper
