// FootprintIndex: one group per keyframe, runs of keyframe-0 rows (see footprint_index.hpp).
#include "mapper/core/footprint_index.hpp"

#include <algorithm>

namespace slam::mapper {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void add_points(MapBox& box, std::span<const Vec2> points) {
  for (const Vec2& p : points) box.add(p);
}

}  // namespace

MapBox box_of(const ObservationView& obs) {
  MapBox box;
  box.add(Vec2{obs.x, obs.y});
  add_points(box, obs.hits);
  add_points(box, obs.misses);
  return box;
}

void FootprintIndex::add(KeyframeId keyframe, int64_t row, const Pose& drawn, const MapBox& box) {
  uint32_t slot = kNone;
  if (keyframe == 0) {
    if (open_run_ != kNone && groups_[open_run_].rows >= kStaticRun) open_run_ = kNone;
    slot = open_run_;
  } else if (const auto it = slot_.find(keyframe); it != slot_.end()) {
    slot = it->second;
  }
  ++observations_;
  if (slot == kNone) {
    slot = static_cast<uint32_t>(groups_.size());
    groups_.push_back(FootprintGroup{keyframe, row, row, 1, drawn, box});
    if (keyframe == 0)
      open_run_ = slot;
    else
      slot_.emplace(keyframe, slot);
    return;
  }
  FootprintGroup& g = groups_[slot];
  g.first_row = std::min(g.first_row, row);
  g.last_row = std::max(g.last_row, row);
  ++g.rows;
  if (!(g.drawn == drawn)) g.drawn = Pose{kNaN, kNaN, kNaN};  // NaN never compares equal: stays mixed
  g.box.add(box);
}

void FootprintIndex::redraw(size_t group, const Pose& drawn, const MapBox& box) {
  groups_[group].drawn = drawn;
  groups_[group].box = box;
}

void FootprintIndex::clear() {
  groups_.clear();
  slot_.clear();
  open_run_ = kNone;
  observations_ = 0;
}

size_t FootprintIndex::memory_bytes() const {
  // An unordered_map node holds the pair and a next pointer (and the cached hash); one bucket pointer each.
  const size_t node = sizeof(std::pair<const KeyframeId, uint32_t>) + 2 * sizeof(void*);
  return groups_.capacity() * sizeof(FootprintGroup) + slot_.size() * node +
         slot_.bucket_count() * sizeof(void*);
}

}  // namespace slam::mapper
