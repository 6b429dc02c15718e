// Mapper compaction (mapper_compaction.cpp): it runs on the worker; observations arriving meanwhile
// are stored after it; the live map, a rebuild of the store and a restarted mapper agree; the
// counters say what was compacted; maybe_compact() waits for the interval.
#include <gtest/gtest.h>

#include <vector>

#include "mapper/core/mapper.hpp"
#include "mapper/core/rebuild.hpp"
#include "mapper_test_data.hpp"
#include "temp_dir.hpp"

namespace slam::mapper {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

class MapperCompaction : public ::testing::Test {
 protected:
  MapperCompaction() {
    options_.store = (dir_.path() / "map.db").string();
    options_.grid = test_data::small();
    options_.grid.width_m = 8.0;
    options_.grid.origin_x = -4.0;
    options_.robot_filter.radius_m = 0.0;
    options_.compaction.retention_days = 100.0 / 86400.0;  // 100 s of gateway stamps
    options_.compaction.min_age_s = 30.0;
    options_.compaction.max_mb = 0.0;
    options_.compaction.interval_s = 10.0;
  }

  std::unique_ptr<Mapper> make() {
    auto mapper = Mapper::create(options_, counters_, 1, [] {});
    EXPECT_TRUE(mapper.is_ok()) << mapper.message();
    return mapper ? std::move(*mapper) : nullptr;
  }

  // Robot r1 at (x, 0) seeing a wall 1.2 m east, stamped `s` seconds; monotonic time `s` too.
  static void feed(Mapper& mapper, uint64_t seq, double x, KeyframeId kf, int64_t s,
                   const Pose& correction = Pose{}) {
    std::vector<Vec2> hits, misses;
    for (int k = -3; k <= 3; ++k) hits.push_back({x + 1.2, 0.1 * k + 0.03});
    misses.push_back({x - 1.5, 0.2});
    const ObservationView v{x, 0.0, 0.0, false, hits, misses};
    mapper.integrate(RobotScan{"r1", seq, s * kSecond, v, kf, correction}, s * kSecond);
  }

  // A full rebuild of what the mapper stored (its open batch committed first).
  OccupancyGrid full_rebuild(Mapper& mapper) {
    mapper.commit();
    auto store = ObservationStore::open(options_.store);
    EXPECT_TRUE(store.is_ok());
    auto grid = rebuild_grid(mapper.grid().config(), *store, nullptr, mapper.corrections());
    EXPECT_TRUE(grid.is_ok()) << grid.message();
    return std::move(*grid);
  }

  static int64_t differing(const OccupancyGrid& a, const OccupancyGrid& b) {
    if (a.width() != b.width() || a.height() != b.height() || a.origin_x() != b.origin_x() ||
        a.origin_y() != b.origin_y())
      return -1;
    int64_t n = 0;
    for (int32_t y = 0; y < a.height(); ++y)
      for (int32_t x = 0; x < a.width(); ++x) n += a.log_odds(x, y) != b.log_odds(x, y) ? 1 : 0;
    return n;
  }

  testkit::TempDir dir_{"mapper-compaction"};
  MapperOptions options_;
  Counters counters_;
};

TEST_F(MapperCompaction, RunsOnTheWorkerAndTheMapRebuildsTheSameAfterARestart) {
  auto mapper = make();
  std::vector<Keyframe> keyframes;
  const auto correction = [](KeyframeId kf) { return Pose{0.01 * static_cast<double>(kf % 3), 0.0, 0.0}; };
  for (KeyframeId kf = 1; kf <= 20; ++kf) keyframes.push_back({kf, "r1", 0, Pose{}, correction(kf)});
  ASSERT_TRUE(mapper->save_keyframes(keyframes));
  // 200 observations over 200 s, ten per keyframe, driving east and back.
  for (int64_t i = 0; i < 200; ++i) {
    const double x = -2.0 + 0.02 * static_cast<double>(i < 100 ? i : 200 - i);
    const auto kf = static_cast<KeyframeId>(1 + i / 10);
    feed(*mapper, static_cast<uint64_t>(i + 1), x, kf, i, correction(kf));
  }
  const OccupancyGrid before = full_rebuild(*mapper);
  EXPECT_EQ(differing(mapper->grid(), before), 0);

  // Keyframes first seen at least 100 s before the newest stamp (199 s): 1..10, rows 1..100.
  ASSERT_TRUE(mapper->compact_now());
  ASSERT_TRUE(mapper->rebuilding());
  feed(*mapper, 201, 0.5, 20, 199,
       correction(20));  // arrives meanwhile: kept aside, stored after the compaction
  mapper->wait_for_rebuild();
  EXPECT_EQ(counters_.get("compactions").load(), 1);
  EXPECT_EQ(counters_.get("compacted_observations").load(), 100);
  EXPECT_EQ(counters_.get("store_observations").load(), 201 - 100);
  EXPECT_EQ(mapper->footprints().observations(), 201 - 100);
  EXPECT_FALSE(mapper->compact_now());  // nothing more is old enough

  const OccupancyGrid live_rebuild = full_rebuild(*mapper);
  EXPECT_EQ(differing(mapper->grid(), live_rebuild), 0);
  const auto stats = [&] {
    auto store = ObservationStore::open(options_.store);
    EXPECT_TRUE(store.is_ok());
    auto s = store->stats();
    EXPECT_TRUE(s.is_ok());
    return *s;
  }();
  EXPECT_EQ(stats.rows, 101);
  EXPECT_EQ(stats.compacted_through, 100);
  EXPECT_EQ(stats.oldest_stamp_ns, 100 * kSecond);

  mapper.reset();
  auto restarted = make();
  EXPECT_EQ(differing(restarted->grid(), live_rebuild), 0);
  EXPECT_EQ(restarted->footprints().observations(), 101);
}

TEST_F(MapperCompaction, MaybeCompactWaitsForTheIntervalAndSkipsRecentlyMovedKeyframes) {
  auto mapper = make();
  std::vector<Keyframe> keyframes;
  for (KeyframeId kf = 1; kf <= 20; ++kf) keyframes.push_back({kf, "r1", 0, Pose{}, Pose{}});
  ASSERT_TRUE(mapper->save_keyframes(keyframes));
  for (int64_t i = 0; i < 150; ++i)
    feed(*mapper, static_cast<uint64_t>(i + 1), -2.0 + 0.02 * static_cast<double>(i),
         static_cast<KeyframeId>(1 + i / 10), i);
  // Keyframe 2 moves (a partial re-render) at stamp 149: it and everything after stay raw.
  ASSERT_TRUE(mapper->save_keyframes(std::vector<Keyframe>{{2, "r1", 0, Pose{}, Pose{0.3, 0.0, 0.0}}}));
  mapper->rerender();
  mapper->wait_for_rebuild();
  ASSERT_EQ(counters_.get("rerenders_partial").load(), 1);
  mapper->poll_rebuild();  // monotonic time 149 s: the first check compacts keyframe 1 (rows 1..10)
  mapper->wait_for_rebuild();
  EXPECT_EQ(counters_.get("compacted_observations").load(), 10);
  feed(*mapper, 151, 1.0, 16, 152);
  mapper->poll_rebuild();  // 3 s later: within the interval, no check
  EXPECT_FALSE(mapper->rebuilding());
  EXPECT_EQ(counters_.get("compactions").load(), 1);
  EXPECT_EQ(differing(mapper->grid(), full_rebuild(*mapper)), 0);
}

}  // namespace
}  // namespace slam::mapper
