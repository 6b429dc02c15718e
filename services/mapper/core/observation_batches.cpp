// The reader → integrator hand-off of the rebuild (see observation_batches.hpp).
#include "mapper/core/observation_batches.hpp"

namespace slam::mapper {

void ObservationBatch::add(int64_t id, const ObservationView& obs, uint64_t keyframe, int64_t stamp_ns) {
  entries.push_back({id, keyframe, stamp_ns, obs.x, obs.y, obs.theta, obs.has_heading,
                     static_cast<uint32_t>(obs.hits.size()), static_cast<uint32_t>(obs.misses.size())});
  points.insert(points.end(), obs.hits.begin(), obs.hits.end());
  points.insert(points.end(), obs.misses.begin(), obs.misses.end());
}

ObservationBatches::ObservationBatches(size_t batches) : storage_(batches) {
  for (ObservationBatch& b : storage_) empty_.push_back(&b);
}

ObservationBatch* ObservationBatches::take_empty() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return !empty_.empty(); });
  ObservationBatch* b = empty_.back();
  empty_.pop_back();
  b->clear();
  return b;
}

void ObservationBatches::push_full(ObservationBatch* batch) {
  {
    std::lock_guard lock(mutex_);
    full_.push_back(batch);
  }
  changed_.notify_all();
}

void ObservationBatches::finish() {
  {
    std::lock_guard lock(mutex_);
    finished_ = true;
  }
  changed_.notify_all();
}

ObservationBatch* ObservationBatches::pop_full() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return finished_ || !full_.empty(); });
  if (full_.empty()) return nullptr;
  ObservationBatch* b = full_.front();
  full_.pop_front();
  return b;
}

void ObservationBatches::give_back(ObservationBatch* batch) {
  {
    std::lock_guard lock(mutex_);
    empty_.push_back(batch);
  }
  changed_.notify_all();
}

}  // namespace slam::mapper
