// Compaction (compaction.hpp): a rebuild from a compacted store equals the map before compaction cell
// for cell (rays and legacy, with a prior, twice over, across grid growth); a partial re-render after
// compaction still equals a full rebuild; new observations outweigh a compacted wall; the plan
// compacts only old, settled keyframes and keeps the newest row; the store reports what it keeps.
#include "mapper/core/compaction.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "mapper/core/partial_rerender.hpp"
#include "mapper/core/rebuild.hpp"
#include "mapper_test_data.hpp"
#include "temp_dir.hpp"

namespace slam::mapper {
namespace {

constexpr double kRange = 4.0;
constexpr int kPerKeyframe = 5;
constexpr int64_t kSecond = 1'000'000'000;

// A room 24 m x 8 m (walls at x = +-12, y = +-4) with a wall segment across x = `inner_x` from y = -1
// to 1 when `inner_wall`; the grid starts 6 m wide, so replaying the store grows it.
GridConfig room_config(bool legacy = false) {
  GridConfig c;
  c.resolution = 0.05;
  c.origin_x = -3.0;
  c.origin_y = -5.0;
  c.width_m = 6.0;
  c.height_m = 10.0;
  c.grow_chunk_m = 2.0;
  c.max_extent_m = 40.0;
  c.inflation_radius = 0.15;
  c.legacy_mode = legacy;
  return c;
}

double cast(double x, double y, double c, double s, bool inner_wall, double inner_x) {
  double best = kRange + 1.0;
  const auto wall = [&](double t) {
    if (t > 1e-9 && t < best) best = t;
  };
  if (std::abs(c) > 1e-12) {
    wall((12.0 - x) / c);
    wall((-12.0 - x) / c);
    if (inner_wall) {
      const double t = (inner_x - x) / c;
      if (std::abs(y + t * s) <= 1.0) wall(t);
    }
  }
  if (std::abs(s) > 1e-12) {
    wall((4.0 - y) / s);
    wall((-4.0 - y) / s);
  }
  return best;
}

// One scan of 72 beams from (x, y).
ObservationView scan(double x, double y, bool inner_wall, double inner_x, std::vector<Vec2>& hits,
                     std::vector<Vec2>& misses) {
  hits.clear();
  misses.clear();
  for (int b = 0; b < 72; ++b) {
    const double a = 2 * std::numbers::pi * b / 72;
    const double c = std::cos(a), s = std::sin(a);
    const double r = cast(x, y, c, s, inner_wall, inner_x);
    (r <= kRange ? hits : misses).push_back({x + std::min(r, kRange) * c, y + std::min(r, kRange) * s});
  }
  return ObservationView{x, y, 0.0, true, hits, misses};
}

struct Fixture {
  testkit::TempDir dir{"compaction"};
  std::optional<ObservationStore> store;
  KeyframeCorrections corrections;
  std::vector<KeyframeId> keyframes;
  int64_t rows = 0;

  Fixture() {
    auto s = ObservationStore::open(dir.path() / "m.db");
    EXPECT_TRUE(s.is_ok()) << s.message();
    store.emplace(std::move(*s));
  }

  // Two robots with keyframes drive the room east and back, a third without keyframes (SLAM off)
  // wanders; observation i is stamped i seconds. Corrections: a few cm each.
  void drive(int steps, int first_step = 0) {
    std::vector<Vec2> hits, misses;
    for (int i = first_step; i < first_step + steps; ++i)
      for (int robot = 0; robot < 3; ++robot) {
        const double t = static_cast<double>(i % 200) / 200;
        const double x = robot == 1 ? 10.0 - 20.0 * t : -10.0 + 20.0 * t;
        const double y = robot == 0 ? -2.0 + std::sin(7 * t) : (robot == 1 ? 2.0 : 2.5 * std::cos(11 * t));
        const KeyframeId kf = robot == 2 ? 0 : static_cast<KeyframeId>(1 + robot * 10000 + i / kPerKeyframe);
        if (kf != 0 && i % kPerKeyframe == 0) {
          keyframes.push_back(kf);
          corrections.set(kf, Pose{0.01 * static_cast<double>(kf % 3), -0.01 * static_cast<double>(kf % 2),
                                   0.001 * static_cast<double>(kf % 5)});
        }
        constexpr const char* kNames[] = {"r0", "r1", "r2"};
        EXPECT_TRUE(store->append(kNames[robot], static_cast<uint64_t>(i), i * kSecond, kf,
                                  scan(x, y, true, 5.0, hits, misses)));
        ++rows;
      }
    EXPECT_TRUE(store->flush());
  }
};

OccupancyGrid rebuild(const GridConfig& config, ObservationStore& store, const KeyframeCorrections& c,
                      FootprintIndex* index = nullptr) {
  auto grid = rebuild_grid(config, store, nullptr, c, index);
  EXPECT_TRUE(grid.is_ok()) << grid.message();
  return std::move(*grid);
}

int64_t compact(const GridConfig& config, ObservationStore& store, const KeyframeCorrections& c,
                int64_t row) {
  auto report = compact_store(config, store, c, row);
  EXPECT_TRUE(report.is_ok()) << report.message();
  return report ? report->rows_deleted : 0;
}

class Compaction : public ::testing::TestWithParam<bool> {};  // legacy mode or not

TEST_P(Compaction, ARebuildFromACompactedStoreEqualsTheMapBeforeCellForCell) {
  Fixture f;
  f.drive(150);
  const GridConfig config = room_config(GetParam());
  const OccupancyGrid before = rebuild(config, *f.store, f.corrections);
  EXPECT_GT(before.width(), 6.0 / config.resolution);  // it grew while replaying

  EXPECT_EQ(compact(config, *f.store, f.corrections, 200), 200);
  test_data::expect_same(rebuild(config, *f.store, f.corrections), before);
  // Again, over the first baseline: still the same map, and far fewer raw rows.
  EXPECT_EQ(compact(config, *f.store, f.corrections, 400), 200);
  test_data::expect_same(rebuild(config, *f.store, f.corrections), before);
  auto count = f.store->count();
  ASSERT_TRUE(count.is_ok());
  EXPECT_EQ(*count, f.rows - 400);

  // And on: the store keeps growing at its end, the map rebuilds equal to the uncompacted one.
  Fixture g;
  g.drive(200);
  f.drive(50, 150);
  test_data::expect_same(rebuild(config, *f.store, f.corrections), rebuild(config, *g.store, g.corrections));
}

TEST_P(Compaction, APriorIsKeptAndOneImportedAfterwardsAppliesOverTheBaseline) {
  Fixture f;
  f.drive(60);
  const GridConfig config = room_config(GetParam());
  MapImage prior;  // free inside, a wall at y = 1 over the west half
  prior.width = 120;
  prior.height = 80;
  prior.resolution = 0.1;
  prior.origin_x = -12.0;
  prior.origin_y = -4.0;
  prior.cells.assign(size_t{prior.width} * prior.height, kMapFree);
  for (uint32_t u = 0; u < prior.width; ++u) prior.cells[50 * size_t{prior.width} + u] = kMapOccupied;
  ASSERT_TRUE(f.store->save_prior(prior));
  const OccupancyGrid before = rebuild(config, *f.store, f.corrections);
  compact(config, *f.store, f.corrections, 90);
  test_data::expect_same(rebuild(config, *f.store, f.corrections), before);

  // A prior imported after the compaction: over the baseline, then the raw rows (as before, with the
  // baseline in place of the observations it holds).
  for (auto& c : prior.cells) c = c == kMapOccupied ? kMapFree : c;
  ASSERT_TRUE(f.store->save_prior(prior));
  auto baseline = f.store->load_baseline();
  ASSERT_TRUE(baseline.is_ok());
  ASSERT_TRUE(baseline->has_value());
  EXPECT_TRUE((*baseline)->prior_pending);
  auto expected = OccupancyGrid::create(config);
  ASSERT_TRUE(expected.is_ok());
  expected->apply_baseline(**baseline);
  ASSERT_TRUE(expected->apply_prior(prior).is_ok());
  ASSERT_TRUE(f.store->for_each([&](const ObservationRecord& rec) {
    std::vector<Vec2> h, m;
    (void)expected->integrate(to_map_frame(f.corrections.lookup(rec.keyframe_id), rec.obs, h, m));
  }));
  const OccupancyGrid after = rebuild(config, *f.store, f.corrections);
  test_data::expect_same(after, *expected);
  // Compacting again folds that prior into the new baseline.
  compact(config, *f.store, f.corrections, 120);
  test_data::expect_same(rebuild(config, *f.store, f.corrections), after);
}

TEST_P(Compaction, APartialRerenderAfterCompactionEqualsAFullRebuild) {
  Fixture f;
  f.drive(160);
  const GridConfig config = room_config(GetParam());
  FootprintIndex index;
  OccupancyGrid grid = rebuild(config, *f.store, f.corrections, &index);
  const int64_t through = 240;  // the first 80 steps of each robot
  index.drop_through(through, compact(config, *f.store, f.corrections, through));
  EXPECT_EQ(index.observations(), f.rows - through);
  for (const FootprintGroup& g : index.groups()) EXPECT_GT(g.first_row, through);

  // Closures move keyframes that keep raw rows, over tiles the baseline covers, and one compacted
  // keyframe (its baked evidence stays where it was drawn; it has no rows left to move).
  KeyframeCorrections wanted = f.corrections;
  const auto move = [&](KeyframeId kf, double dx, double dy, double dt) {
    const Pose p = wanted.lookup(kf);
    wanted.set(kf, Pose{p.x + dx, p.y + dy, p.theta + dt});
  };
  for (KeyframeId kf = 20; kf <= 23; ++kf) move(kf, 0.15, -0.1, 0.01);
  move(10000 + 25, -0.2, 0.1, -0.02);
  move(3, 0.3, 0.3, 0.05);  // compacted
  const RerenderDecision d = plan_rerender(index, wanted, grid, RerenderOptions{});
  ASSERT_EQ(d.kind, RerenderDecision::Kind::Partial) << d.reason;
  auto render = render_tiles(d.plan, *f.store);
  ASSERT_TRUE(render.is_ok()) << render.message();
  ASSERT_FALSE(render->outside_grid);
  grid.redraw(render->canvas);
  record_redraw(*render, index);
  test_data::expect_same(grid, rebuild(config, *f.store, wanted));
}

INSTANTIATE_TEST_SUITE_P(Modes, Compaction, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& p) { return p.param ? "Legacy" : "Rays"; });

TEST(CompactionChange, NewObservationsOutweighACompactedWall) {
  // A wall across x = 5 seen by 300 scans (saturated, then compacted); the wall is taken away and
  // new scans see through it: its cells turn free, in the live grid as in a rebuild.
  Fixture f;
  const GridConfig config = room_config();
  std::vector<Vec2> hits, misses;
  for (int i = 0; i < 300; ++i)
    ASSERT_TRUE(f.store->append("r0", static_cast<uint64_t>(i), i * kSecond, 0,
                                scan(3.0 + 0.002 * (i % 10), 0.0, true, 5.0, hits, misses)));
  ASSERT_TRUE(f.store->flush());
  const OccupancyGrid walled = rebuild(config, *f.store, {});
  const auto wall = walled.cell_at({5.02, 0.0});
  ASSERT_TRUE(wall.has_value());
  EXPECT_EQ(walled.log_odds(wall->x, wall->y), config.log_odds.clamp_max);
  EXPECT_EQ(compact(config, *f.store, {}, 299), 299);

  const OccupancyGrid compacted = rebuild(config, *f.store, {});
  EXPECT_TRUE(is_wall(compacted.cell_class(wall->x, wall->y)));
  for (int i = 300; i < 330; ++i)
    ASSERT_TRUE(f.store->append("r0", static_cast<uint64_t>(i), i * kSecond, 0,
                                scan(3.0 + 0.002 * (i % 10), 0.0, false, 5.0, hits, misses)));
  ASSERT_TRUE(f.store->flush());
  const OccupancyGrid after = rebuild(config, *f.store, {});
  EXPECT_EQ(after.cell_class(wall->x, wall->y) & kCellStateMask, kCellFree);
  EXPECT_LE(after.log_odds(wall->x, wall->y), config.log_odds.free_threshold);
}

// An index of groups: (keyframe, first row, last row, first stamp s, moved stamp s).
FootprintIndex index_of(
    std::initializer_list<std::tuple<KeyframeId, int64_t, int64_t, int64_t, int64_t>> gs) {
  FootprintIndex index;
  for (const auto& [kf, first, last, stamp, moved] : gs) {
    for (int64_t row = first; row <= last; ++row) index.add(kf, row, Pose{}, MapBox{}, stamp * kSecond);
    if (moved > 0) index.redraw(index.groups().size() - 1, Pose{}, MapBox{}, moved * kSecond);
  }
  return index;
}

TEST(CompactionPlan, OnlyOldSettledKeyframesAndNeverTheNewestRow) {
  CompactionOptions o;
  o.retention_days = 1.0;
  o.min_age_s = 600.0;
  o.max_mb = 0.0;
  const int64_t day = 86400;
  const int64_t now = 10 * day * kSecond;
  // Keyframes 1..3 are two days old, 4 is young: rows up to 3's last.
  FootprintIndex index = index_of({{1, 1, 10, 8 * day, 0},
                                   {2, 11, 20, 8 * day, 0},
                                   {3, 21, 30, 8 * day, 0},
                                   {4, 31, 40, 10 * day - 100, 0}});
  auto plan = plan_compaction(index, now, 0, 0, o);
  ASSERT_TRUE(plan.has_value());
  EXPECT_EQ(plan->through_row, 30);
  EXPECT_EQ(plan->groups, 3u);
  index.drop_through(30, 30);
  EXPECT_FALSE(plan_compaction(index, now, 0, 0, o).has_value());  // done already
  // A robot reset deleted every raw row: SQLite numbers new rows from 1 again, below the baseline's
  // row; they are compacted all the same (the newest stays).
  FootprintIndex renumbered = index_of({{7, 1, 4, 8 * day, 0}, {8, 5, 6, 8 * day, 0}});
  auto again = plan_compaction(renumbered, now, 0, 0, o);
  ASSERT_TRUE(again.has_value());
  EXPECT_EQ(again->through_row, 5);
  // A keyframe moved recently holds back its rows and every later one.
  index = index_of({{1, 1, 10, 8 * day, 0}, {2, 11, 20, 8 * day, 10 * day - 60}, {3, 21, 30, 8 * day, 0}});
  plan = plan_compaction(index, now, 0, 0, o);
  ASSERT_TRUE(plan.has_value());
  EXPECT_EQ(plan->through_row, 10);
  // A full re-render just now: nothing.
  EXPECT_FALSE(plan_compaction(index, now, 0, now - 60 * kSecond, o).has_value());
  // All old: the newest row stays.
  index = index_of({{1, 1, 10, 8 * day, 0}, {0, 11, 20, 8 * day, 0}});
  plan = plan_compaction(index, now, 0, 0, o);
  ASSERT_TRUE(plan.has_value());
  EXPECT_EQ(plan->through_row, 19);
  // Young by retention, but the store is over its size: compacted down to min_age_s.
  index = index_of({{1, 1, 10, now / kSecond - 3600, 0}, {2, 11, 20, now / kSecond - 60, 0}});
  EXPECT_FALSE(plan_compaction(index, now, 0, 0, o).has_value());
  o.max_mb = 1.0;
  plan = plan_compaction(index, now, 2 * 1024 * 1024, 0, o);
  ASSERT_TRUE(plan.has_value());
  EXPECT_EQ(plan->through_row, 10);
  EXPECT_FALSE(plan_compaction(index, now, 512 * 1024, 0, o).has_value());  // within its size
}

TEST(CompactionOptions, BadValuesNameTheirKey) {
  CompactionOptions o;
  EXPECT_TRUE(validate(o));
  o.retention_days = -1.0;
  EXPECT_NE(validate(o).message().find("store.retention_days"), std::string::npos);
  o = {};
  o.max_mb = std::nan("");
  EXPECT_NE(validate(o).message().find("store.max_mb"), std::string::npos);
  o = {};
  o.interval_s = 0.0;
  EXPECT_NE(validate(o).message().find("store.compact_interval_s"), std::string::npos);
}

TEST(CompactionStore, StatsSayWhatIsKeptAndTheBaselineSurvivesAReopen) {
  Fixture f;
  f.drive(40);
  const GridConfig config = room_config();
  auto before = f.store->stats();
  ASSERT_TRUE(before.is_ok()) << before.message();
  EXPECT_EQ(before->rows, f.rows);
  EXPECT_EQ(before->compacted_tiles, 0);
  EXPECT_EQ(before->compacted_through, 0);
  EXPECT_EQ(before->oldest_stamp_ns, 0);
  EXPECT_EQ(before->newest_stamp_ns, 39 * kSecond);
  EXPECT_EQ(before->raw_keyframes, 16);
  EXPECT_GT(before->bytes, 0);
  compact(config, *f.store, f.corrections, 60);
  auto after = f.store->stats();
  ASSERT_TRUE(after.is_ok()) << after.message();
  EXPECT_EQ(after->rows, f.rows - 60);
  EXPECT_GT(after->compacted_tiles, 0);
  EXPECT_EQ(after->compacted_through, 60);
  EXPECT_EQ(after->oldest_stamp_ns, 20 * kSecond);
  EXPECT_EQ(after->raw_keyframes, 8);
  const OccupancyGrid map = rebuild(config, *f.store, f.corrections);
  f.store.reset();
  auto reopened = ObservationStore::open(f.dir.path() / "m.db");
  ASSERT_TRUE(reopened.is_ok()) << reopened.message();
  test_data::expect_same(rebuild(config, *reopened, f.corrections), map);
}

TEST(FootprintIndexDrop, GroupsWhollyCompactedGoTheOthersKeepTheirLaterRows) {
  FootprintIndex index = index_of({{1, 1, 10, 0, 0}, {2, 5, 20, 0, 0}, {0, 21, 22, 0, 0}});
  index.drop_through(10, 15);
  ASSERT_EQ(index.groups().size(), 2u);
  EXPECT_EQ(index.observations(), 13);
  EXPECT_EQ(index.groups()[0].keyframe, 2u);
  EXPECT_EQ(index.groups()[0].first_row, 11);
  // Later rows find their groups: keyframe 2's and the open keyframe-0 run.
  index.add(2, 23, Pose{}, MapBox{});
  index.add(0, 24, Pose{}, MapBox{});
  index.add(1, 25, Pose{}, MapBox{});
  ASSERT_EQ(index.groups().size(), 3u);
  EXPECT_EQ(index.groups()[0].last_row, 23);
  EXPECT_EQ(index.groups()[1].last_row, 24);
  EXPECT_EQ(index.groups()[2].keyframe, 1u);
}

}  // namespace
}  // namespace slam::mapper
