#pragma once
// Where the stored observations lie in the grid as it is drawn, per keyframe: the correction its
// observations were drawn with and the map-frame box they cover (sensor origins, hits and misses:
// every ray lies inside). A re-render asks it which keyframes moved and which others touch the tiles
// those leave or enter, and replays only those (partial_rerender.hpp). One entry of about 100 bytes per
// keyframe (plus its hash slot), never per observation; every full rebuild (start-up included)
// builds it afresh from the store and the mapper extends it as it stores observations.
// Observations without a keyframe (id 0) never move but may lie in a redrawn tile: they are kept in
// runs of consecutive rows, so they are found too. Plain C++, not thread-safe.
#include <cstdint>
#include <limits>
#include <span>
#include <unordered_map>
#include <vector>

#include "common/core/geometry.hpp"
#include "mapper/core/corrections.hpp"
#include "mapper/core/occupancy_grid.hpp"

namespace slam::mapper {

// A map-frame box in metres; empty until a point is added.
struct MapBox {
  double x0 = std::numeric_limits<double>::infinity();
  double y0 = std::numeric_limits<double>::infinity();
  double x1 = -std::numeric_limits<double>::infinity();
  double y1 = -std::numeric_limits<double>::infinity();

  bool empty() const { return !(x0 <= x1 && y0 <= y1); }
  void add(Vec2 p) {
    x0 = p.x < x0 ? p.x : x0;
    y0 = p.y < y0 ? p.y : y0;
    x1 = p.x > x1 ? p.x : x1;
    y1 = p.y > y1 ? p.y : y1;
  }
  void add(const MapBox& b) {
    if (b.empty()) return;
    add(Vec2{b.x0, b.y0});
    add(Vec2{b.x1, b.y1});
  }
  bool operator==(const MapBox&) const = default;
};

// The box of an observation as drawn (map frame): its sensor origin and every point.
MapBox box_of(const ObservationView& obs);

// The observations of one keyframe (or one run of keyframe-0 rows) as the grid has them.
struct FootprintGroup {
  KeyframeId keyframe = 0;
  int64_t first_row = 0;  // store rows: its observations lie in [first_row, last_row]
  int64_t last_row = 0;
  int64_t rows = 0;
  Pose drawn;  // the correction they are drawn with; NaN when drawn with several (a re-render redraws all)
  MapBox box;  // where they are drawn
  int64_t first_stamp_ns = 0;  // its first observation's gateway stamp (how old it is)
  int64_t moved_stamp_ns = 0;  // the newest stamp stored when it was last redrawn at a new correction
};

class FootprintIndex {
 public:
  // Keyframe-0 rows per run: a run's box grows with its robots' paths, so runs stay short.
  static constexpr int64_t kStaticRun = 256;

  // Stored row `row` of `keyframe` (gateway stamp `stamp_ns`), drawn with `drawn` over `box`.
  void add(KeyframeId keyframe, int64_t row, const Pose& drawn, const MapBox& box, int64_t stamp_ns = 0);
  // Group `group`'s observations are drawn again, with `drawn` over `box` (at `stamp_ns`, the newest
  // stamp stored then).
  void redraw(size_t group, const Pose& drawn, const MapBox& box, int64_t stamp_ns = 0);
  // The rows up to `row` are compacted into the baseline: groups with no row after it go, the others
  // keep their rows after it (their boxes stay: they still hold every remaining row). `deleted`: how
  // many rows that was (the index counts observations, not rows per group).
  void drop_through(int64_t row, int64_t deleted);
  void clear();

  std::span<const FootprintGroup> groups() const { return groups_; }
  // Observations indexed (stored and drawn).
  int64_t observations() const { return observations_; }
  // Heap bytes held (the groups and the keyframe lookup), for the log and the tests.
  size_t memory_bytes() const;

 private:
  static constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
  std::vector<FootprintGroup> groups_;
  std::unordered_map<KeyframeId, uint32_t> slot_;  // keyframe (not 0) -> its group
  uint32_t open_run_ = kNone;                      // the keyframe-0 run being filled
  int64_t observations_ = 0;
};

}  // namespace slam::mapper
