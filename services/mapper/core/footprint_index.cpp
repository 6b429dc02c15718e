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

void FootprintIndex::add(KeyframeId keyframe, int64_t row, const Pose& drawn, const MapBox& box,
                         int64_t stamp_ns) {
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
    groups_.push_back(FootprintGroup{keyframe, row, row, 1, drawn, box, stamp_ns, 0});
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

void FootprintIndex::redraw(size_t group, const Pose& drawn, const MapBox& box, int64_t stamp_ns) {
  groups_[group].drawn = drawn;
  groups_[group].box = box;
  groups_[group].moved_stamp_ns = stamp_ns;
}

void FootprintIndex::drop_through(int64_t row, int64_t deleted) {
  const FootprintGroup* open = open_run_ == kNone ? nullptr : &groups_[open_run_];
  const bool open_kept = open && open->last_row > row;
  size_t kept = 0;
  uint32_t new_open = kNone;
  for (size_t i = 0; i < groups_.size(); ++i) {
    FootprintGroup g = groups_[i];
    if (g.last_row <= row) continue;
    if (g.first_row <= row) {
      // Rows are not counted per row here: the ones kept are at most what it had, at least one.
      g.first_row = row + 1;
    }
    if (open_kept && i == open_run_) new_open = static_cast<uint32_t>(kept);
    groups_[kept++] = g;
  }
  groups_.resize(kept);
  open_run_ = new_open;
  slot_.clear();
  for (size_t i = 0; i < groups_.size(); ++i)
    if (groups_[i].keyframe != 0) slot_.emplace(groups_[i].keyframe, static_cast<uint32_t>(i));
  observations_ -= deleted;
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
