#pragma once
// Decoded observations handed from a reader thread to the thread that integrates them, in order
// and in a few reused batches of flat arrays: the rebuild reads SQLite on one core while it
// ray-casts on the other, and memory stays bounded whatever the store's size.
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <span>
#include <vector>

#include "mapper/core/occupancy_grid.hpp"

namespace slam::mapper {

// Observations back to back: entry i's hits, then its misses, follow entry i-1's in `points`.
struct ObservationBatch {
  struct Entry {
    int64_t id = 0;         // the store's row id
    uint64_t keyframe = 0;  // its keyframe (0: none)
    int64_t stamp_ns = 0;   // its gateway stamp
    double x = 0.0, y = 0.0, theta = 0.0;
    bool has_heading = false;
    uint32_t hits = 0;
    uint32_t misses = 0;
  };
  std::vector<Entry> entries;
  std::vector<Vec2> points;

  void clear() {
    entries.clear();
    points.clear();
  }
  // Copies `obs` in (the spans it points at may be reused by the caller).
  void add(int64_t id, const ObservationView& obs, uint64_t keyframe = 0, int64_t stamp_ns = 0);
  // Calls visit(entry, view) for each entry in order; the views point into this batch.
  template <class Visit>
  void for_each_entry(Visit&& visit) const {
    size_t at = 0;
    for (const Entry& e : entries) {
      const std::span<const Vec2> hits(points.data() + at, e.hits);
      const std::span<const Vec2> misses(points.data() + at + e.hits, e.misses);
      at += size_t{e.hits} + e.misses;
      visit(e, ObservationView{e.x, e.y, e.theta, e.has_heading, hits, misses});
    }
  }
  // Calls visit(id, view) for each entry in order.
  template <class Visit>
  void for_each(Visit&& visit) const {
    for_each_entry([&](const Entry& e, const ObservationView& v) { visit(e.id, v); });
  }
};

// The hand-off between one producer and one consumer. `batches` are allocated once; the producer
// fills an empty one and pushes it, the consumer pops full ones in push order and gives them back.
class ObservationBatches {
 public:
  explicit ObservationBatches(size_t batches);

  // Producer: an empty batch to fill (waits until the consumer gave one back).
  ObservationBatch* take_empty();
  void push_full(ObservationBatch* batch);
  // Producer: nothing more will be pushed.
  void finish();

  // Consumer: the next full batch in order; nullptr when the producer finished and all were popped.
  ObservationBatch* pop_full();
  void give_back(ObservationBatch* batch);

 private:
  std::vector<ObservationBatch> storage_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<ObservationBatch*> empty_;
  std::deque<ObservationBatch*> full_;
  bool finished_ = false;
};

}  // namespace slam::mapper
