#pragma once
// What the DDS reader callbacks hand to the map loop: copies of the samples behind one mutex.
// Callbacks only push (short, never blocking on the grid); the loop waits here and takes everything in
// one go. Requests keep their arrival order across kinds, since an edit after a layout change must
// apply to the new layout. Observations are bounded: past the bound they are dropped and counted.
#include <slam/fastdds/correction.h>
#include <slam/fastdds/robot.h>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <utility>
#include <vector>

#include "mapper/core/mapper.hpp"

namespace slam::mapper {

struct MapperBatch {
  std::vector<slam::RobotObservation> observations;      // in arrival order
  std::vector<MapCommand> commands;                      // in arrival order
  std::vector<slam::InitialPose> initial_poses;          // in arrival order
  std::vector<slam::PlacementAnswer> placement_answers;  // in arrival order
  uint64_t dropped = 0;                                  // observations dropped since the last drain

  void clear();
};

class MapperIntake {
 public:
  explicit MapperIntake(size_t max_observations) : max_observations_(max_observations) {}

  void push(const slam::RobotObservationBatch& batch);  // each observation, in order
  void push(MapCommand command);
  void push(const slam::InitialPose& request);
  void push(const slam::PlacementAnswer& request);
  // Wakes the loop now (a rebuild finished, a keyframe's match landed).
  void notify();

  // Sleeps until `deadline`, a request or notify() (requests deserve an answer now; observations wait
  // for the next patch tick so they are integrated in batches).
  void wait_until(std::chrono::steady_clock::time_point deadline);
  // Moves everything queued into `out` (cleared first; its buffers are recycled).
  void drain(MapperBatch& out);

 private:
  // Queues a request and wakes the loop: it deserves an answer now.
  template <typename Request>
  void push_urgent(std::vector<Request>& queue, Request request) {
    {
      std::lock_guard lock(mutex_);
      queue.push_back(std::move(request));
      urgent_ = true;
    }
    wake_.notify_one();
  }

  const size_t max_observations_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool urgent_ = false;
  MapperBatch pending_;
};

}  // namespace slam::mapper
