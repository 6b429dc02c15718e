// OccupancyGrid: ray updates, clamping and thresholds, one update per cell per observation,
// inflation, obstructions, growth and its limit, legacy mode, bad input and dirty tracking.
#include "mapper/core/occupancy_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace slam::mapper {
namespace {

GridConfig small_config() {
  GridConfig c;
  c.resolution = 1.0;
  c.origin_x = 0.0;
  c.origin_y = 0.0;
  c.width_m = 10.0;
  c.height_m = 10.0;
  c.inflation_radius = 0.0;
  c.max_extent_m = 50.0;
  c.grow_chunk_m = 5.0;
  c.max_range_m = 40.0;
  return c;
}

OccupancyGrid make(const GridConfig& c = small_config()) {
  auto g = OccupancyGrid::create(c);
  EXPECT_TRUE(g.is_ok()) << g.message();
  return std::move(*g);
}

Result<IntegrateStats> shoot(OccupancyGrid& g, Vec2 from, std::vector<Vec2> hits,
                             std::vector<Vec2> misses = {}) {
  ObservationView v;
  v.x = from.x;
  v.y = from.y;
  v.hits = hits;
  v.misses = misses;
  return g.integrate(v);
}

uint8_t state(const OccupancyGrid& g, int x, int y) {
  return g.cell_class(x, y) & kCellStateMask;
}

TEST(OccupancyGrid, StartsUnknown) {
  const OccupancyGrid g = make();
  EXPECT_EQ(g.width(), 10);
  EXPECT_EQ(g.height(), 10);
  for (uint8_t c : g.classes()) EXPECT_EQ(c, kCellUnknown);
}

TEST(OccupancyGrid, HitClearsRayAndMarksEnd) {
  OccupancyGrid g = make();
  auto r = shoot(g, {0.5, 0.5}, {{5.5, 0.5}});
  ASSERT_TRUE(r.is_ok()) << r.message();
  EXPECT_EQ(r->hits, 1u);
  EXPECT_EQ(r->cells_traced, 5);
  for (int x = 0; x < 5; ++x) EXPECT_EQ(state(g, x, 0), kCellFree) << x;
  EXPECT_EQ(state(g, 5, 0), kCellOccupied);
  EXPECT_EQ(g.log_odds(5, 0), g.config().log_odds.hit);
  EXPECT_EQ(state(g, 6, 0), kCellUnknown);
}

TEST(OccupancyGrid, MissClearsRayButLeavesEndUnknown) {
  OccupancyGrid g = make();
  ASSERT_TRUE(shoot(g, {0.5, 0.5}, {}, {{0.5, 4.5}}).is_ok());
  for (int y = 0; y < 4; ++y) EXPECT_EQ(state(g, 0, y), kCellFree);
  EXPECT_EQ(state(g, 0, 4), kCellUnknown);
  EXPECT_EQ(g.log_odds(0, 4), 0);
}

TEST(OccupancyGrid, LogOddsClampBothWays) {
  OccupancyGrid g = make();
  for (int i = 0; i < 30; ++i) ASSERT_TRUE(shoot(g, {0.5, 0.5}, {{5.5, 0.5}}).is_ok());
  EXPECT_EQ(g.log_odds(5, 0), g.config().log_odds.clamp_max);
  EXPECT_EQ(g.log_odds(2, 0), g.config().log_odds.clamp_min);
}

TEST(OccupancyGrid, ThresholdsAreConfigurable) {
  GridConfig c = small_config();
  c.log_odds.occupied_threshold = 150;  // two hits needed
  c.log_odds.free_threshold = -70;      // two misses needed
  OccupancyGrid g = make(c);
  ASSERT_TRUE(shoot(g, {0.5, 0.5}, {{3.5, 0.5}}).is_ok());
  EXPECT_EQ(state(g, 3, 0), kCellUnknown);
  EXPECT_EQ(state(g, 1, 0), kCellUnknown);
  ASSERT_TRUE(shoot(g, {0.5, 0.5}, {{3.5, 0.5}}).is_ok());
  EXPECT_EQ(state(g, 3, 0), kCellOccupied);
  EXPECT_EQ(state(g, 1, 0), kCellFree);
}

TEST(OccupancyGrid, OneUpdatePerCellPerObservation) {
  OccupancyGrid g = make();
  // Many beams from one origin share the cells near the robot: each cell gets one miss.
  std::vector<Vec2> misses;
  for (int i = 0; i < 50; ++i) misses.push_back({8.5, 0.5 + 0.01 * i});
  ASSERT_TRUE(shoot(g, {0.5, 0.5}, {}, misses).is_ok());
  EXPECT_EQ(g.log_odds(1, 0), g.config().log_odds.miss);
  // A ray through a cell another beam of the same observation hit does not clear it.
  OccupancyGrid h = make();
  ASSERT_TRUE(shoot(h, {0.5, 0.5}, {{4.5, 0.5}, {8.5, 0.5}}).is_ok());
  EXPECT_EQ(h.log_odds(4, 0), h.config().log_odds.hit);
  EXPECT_EQ(state(h, 4, 0), kCellOccupied);
}

TEST(OccupancyGrid, StampWrapAroundKeepsCountingUpdates) {
  OccupancyGrid g = make();
  ASSERT_TRUE(shoot(g, {0.5, 5.5}, {}, {{4.5, 5.5}}).is_ok());  // stamp 1 on row 5
  // 65534 more observations elsewhere: the next one reuses stamp 1 after the wrap.
  for (int i = 0; i < 65534; ++i) ASSERT_TRUE(shoot(g, {0.5, 0.5}, {}, {{2.5, 0.5}}).is_ok());
  ASSERT_TRUE(shoot(g, {0.5, 5.5}, {}, {{4.5, 5.5}}).is_ok());
  EXPECT_EQ(g.log_odds(1, 5), 2 * g.config().log_odds.miss);
}

TEST(OccupancyGrid, PassingRobotCannotEraseEstablishedWall) {
  OccupancyGrid g = make();
  for (int i = 0; i < 10; ++i)
    ASSERT_TRUE(shoot(g, {0.5, 0.5}, {{5.5, 0.5}}).is_ok());  // several robots saw it
  for (int i = 0; i < 10; ++i)
    ASSERT_TRUE(shoot(g, {0.5, 0.5}, {}, {{9.5, 0.5}}).is_ok());  // one sees through
  EXPECT_EQ(state(g, 5, 0), kCellOccupied);
}

TEST(OccupancyGrid, InflationFollowsOccupiedCells) {
  GridConfig c = small_config();
  c.inflation_radius = 1.5;
  OccupancyGrid g = make(c);
  ASSERT_TRUE(shoot(g, {0.5, 5.5}, {{5.5, 5.5}}).is_ok());
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      EXPECT_TRUE(g.cell_class(5 + dx, 5 + dy) & kCellInflated) << dx << "," << dy;
  EXPECT_FALSE(g.cell_class(7, 5) & kCellInflated);
  EXPECT_FALSE(g.cell_class(5, 7) & kCellInflated);
  EXPECT_EQ(g.inflation_count(5, 6), 1);
  // See through it until it is no longer occupied: the inflation goes with it.
  for (int i = 0; i < 4; ++i) ASSERT_TRUE(shoot(g, {0.5, 5.5}, {}, {{9.5, 5.5}}).is_ok());
  EXPECT_NE(state(g, 5, 5), kCellOccupied);
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x) {
      EXPECT_FALSE(g.cell_class(x, y) & kCellInflated) << x << "," << y;
      EXPECT_EQ(g.inflation_count(x, y), 0);
    }
}

TEST(OccupancyGrid, ObstructionsFlagInflateAndRemove) {
  GridConfig c = small_config();
  c.inflation_radius = 1.0;
  OccupancyGrid g = make(c);
  ASSERT_TRUE(g.obstruct(3.2, 3.7).is_ok());
  ASSERT_TRUE(g.obstruct(3.9, 3.1).is_ok());  // same cell: kept once
  EXPECT_TRUE(g.cell_class(3, 3) & kCellObstructed);
  EXPECT_EQ(state(g, 3, 3), kCellUnknown);  // observed state stays what robots saw
  EXPECT_TRUE(g.cell_class(4, 3) & kCellInflated);
  EXPECT_EQ(g.obstructions().size(), 1u);
  const auto removed = g.unobstruct(3.5, 3.5);
  ASSERT_EQ(removed.size(), 1u);
  EXPECT_EQ(removed[0], (Vec2{3.2, 3.7}));
  EXPECT_EQ(g.cell_class(3, 3), kCellUnknown);
  EXPECT_FALSE(g.cell_class(4, 3) & kCellInflated);
  ASSERT_TRUE(g.obstruct(1.5, 1.5).is_ok());
  ASSERT_TRUE(g.obstruct(8.5, 8.5).is_ok());
  g.clear_obstructions();
  EXPECT_TRUE(g.obstructions().empty());
  for (uint8_t cls : g.classes()) EXPECT_EQ(cls, kCellUnknown);
  EXPECT_FALSE(g.obstruct(std::nan(""), 1.0).is_ok());
}

TEST(OccupancyGrid, GrowsInChunksAndKeepsContents) {
  OccupancyGrid g = make();
  ASSERT_TRUE(shoot(g, {0.5, 0.5}, {{5.5, 0.5}}).is_ok());
  const uint32_t layout = g.layout_version();
  auto r = shoot(g, {2.5, 2.5}, {{-3.5, 2.5}, {12.5, 2.5}});
  ASSERT_TRUE(r.is_ok()) << r.message();
  EXPECT_TRUE(r->grew);
  EXPECT_GT(g.layout_version(), layout);
  EXPECT_DOUBLE_EQ(g.origin_x(), -5.0);  // grew by one 5-cell chunk to the left
  EXPECT_EQ(g.width(), 20);              // and one to the right
  EXPECT_EQ(g.height(), 10);
  std::optional<Cell> c;
  c = g.cell_at({5.5, 0.5});
  ASSERT_TRUE(c);
  EXPECT_EQ(state(g, c->x, c->y), kCellOccupied);
  c = g.cell_at({-3.5, 2.5});
  ASSERT_TRUE(c);
  EXPECT_EQ(state(g, c->x, c->y), kCellOccupied);
  c = g.cell_at({12.5, 2.5});
  ASSERT_TRUE(c);
  EXPECT_EQ(state(g, c->x, c->y), kCellOccupied);
  const DirtyTiles& dirty = g.dirty_tiles();
  EXPECT_EQ(dirty.layout().width, g.width());
  EXPECT_EQ(dirty.layout().height, g.height());
  for (uint32_t t = 0; t < dirty.layout().count(); ++t) EXPECT_TRUE(dirty.marked(t)) << t;
}

TEST(OccupancyGrid, GrowthStopsAtMaxExtentAndClipsRays) {
  GridConfig c = small_config();
  c.max_extent_m = 20.0;
  OccupancyGrid g = make(c);
  auto r = shoot(g, {0.5, 0.5}, {{30.5, 0.5}});
  ASSERT_TRUE(r.is_ok()) << r.message();
  EXPECT_EQ(r->clipped, 1u);
  EXPECT_EQ(r->hits, 0u);
  EXPECT_EQ(g.width(), 20);
  for (int x = 0; x < g.width(); ++x) EXPECT_EQ(state(g, x, 0), kCellFree) << x;

  const std::vector<uint8_t> before(g.classes().begin(), g.classes().end());
  auto far = shoot(g, {35.5, 0.5}, {{36.5, 0.5}});
  ASSERT_FALSE(far.is_ok());
  EXPECT_NE(far.message().find("maximum map extent"), std::string::npos) << far.message();
  EXPECT_EQ(std::vector<uint8_t>(g.classes().begin(), g.classes().end()), before);
}

TEST(OccupancyGrid, LegacyModeMarksPointsAndClearsNothing) {
  GridConfig c = small_config();
  c.legacy_mode = true;
  OccupancyGrid g = make(c);
  ASSERT_TRUE(shoot(g, {0.5, 0.5}, {{5.5, 0.5}}, {{0.5, 8.5}}).is_ok());
  EXPECT_EQ(state(g, 5, 0), kCellOccupied);
  EXPECT_EQ(g.log_odds(5, 0), c.log_odds.clamp_max);
  for (int x = 0; x < 5; ++x) EXPECT_EQ(state(g, x, 0), kCellUnknown);
  for (int y = 1; y < 9; ++y) EXPECT_EQ(state(g, 0, y), kCellUnknown);
}

TEST(OccupancyGrid, BadInputLeavesGridUntouched) {
  OccupancyGrid g = make();
  ASSERT_TRUE(shoot(g, {0.5, 0.5}, {{5.5, 0.5}}).is_ok());
  g.clear_dirty();
  const std::vector<uint8_t> before(g.classes().begin(), g.classes().end());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  auto a = shoot(g, {0.5, 0.5}, {{1.5, 0.5}, {nan, 1.0}});
  ASSERT_FALSE(a.is_ok());
  EXPECT_NE(a.message().find("hit 1"), std::string::npos) << a.message();
  EXPECT_FALSE(shoot(g, {inf, 0.5}, {{1.5, 0.5}}).is_ok());
  EXPECT_FALSE(shoot(g, {0.5, 0.5}, {}, {{0.5, -inf}}).is_ok());
  auto far = shoot(g, {0.5, 0.5}, {{1.5, 0.5}, {1e9, 0.5}});
  ASSERT_FALSE(far.is_ok());
  EXPECT_NE(far.message().find("max_range_m"), std::string::npos) << far.message();
  EXPECT_EQ(std::vector<uint8_t>(g.classes().begin(), g.classes().end()), before);
  EXPECT_FALSE(g.dirty_tiles().any());
  EXPECT_EQ(g.width(), 10);
}

TEST(OccupancyGrid, InvalidConfigIsRejectedWithTheKey) {
  const auto expect_bad = [](GridConfig c, const char* key) {
    auto g = OccupancyGrid::create(c);
    ASSERT_FALSE(g.is_ok()) << key;
    EXPECT_EQ(g.message().rfind(key, 0), 0u) << g.message();
  };
  GridConfig c = small_config();
  c.resolution = 0.0;
  expect_bad(c, "resolution");
  c.resolution = -0.05;
  expect_bad(c, "resolution");
  c = small_config();
  c.width_m = std::nan("");
  expect_bad(c, "width_m");
  c = small_config();
  c.resolution = 0.001;
  c.width_m = c.height_m = c.max_extent_m = 1000.0;  // a million cells per side
  expect_bad(c, "max_extent_m");
  c = small_config();
  c.width_m = 60.0;
  expect_bad(c, "max_extent_m");
  c = small_config();
  c.inflation_radius = 500.0;
  expect_bad(c, "inflation_radius");
  c = small_config();
  c.log_odds.miss = 5;
  expect_bad(c, "log_odds.miss");
  c = small_config();
  c.log_odds.free_threshold = 10;
  expect_bad(c, "log_odds.free_threshold");
}

TEST(OccupancyGrid, DirtyTilesCoverChangesAndEncodeTheirCells) {
  OccupancyGrid g = make();
  EXPECT_FALSE(g.dirty_tiles().any());
  ASSERT_TRUE(shoot(g, {1.5, 2.5}, {{4.5, 2.5}}).is_ok());
  ASSERT_TRUE(g.dirty_tiles().any());
  EncodedTiles encoded;
  encode_tiles(g.classes(), g.dirty_tiles(), encoded);
  EXPECT_EQ(encoded.tiles, (std::vector<uint32_t>{0}));
  // Decoded over an all-unknown grid, the patch gives the grid's cells back.
  std::vector<uint8_t> mirror(g.classes().size(), kCellUnknown);
  const TilePatchView view{static_cast<uint32_t>(kGridTileSide), static_cast<uint8_t>(encoded.encoding),
                           encoded.tiles, encoded.data};
  ASSERT_TRUE(apply_tiles(view, mirror, g.width(), g.height()));
  EXPECT_EQ(mirror, std::vector<uint8_t>(g.classes().begin(), g.classes().end()));
  // Radius 0: an occupied cell inflates only itself.
  EXPECT_EQ(g.cell_class(4, 2), kCellOccupied | kCellInflated);
  g.clear_dirty();
  EXPECT_FALSE(g.dirty_tiles().any());
  // Re-observing the same thing changes log-odds but no class: nothing to publish.
  ASSERT_TRUE(shoot(g, {1.5, 2.5}, {{4.5, 2.5}}).is_ok());
  EXPECT_FALSE(g.dirty_tiles().any());
}

// Every class change, inflation included, marks its tile: a mirror fed only the encoded dirty
// tiles after each observation equals the grid cell for cell (a 70 x 45 grid: clipped edge tiles).
TEST(OccupancyGrid, DirtyTilesCarryEveryChangeToAMirror) {
  GridConfig c = small_config();
  c.resolution = 0.1;
  c.width_m = 7.0;
  c.height_m = 4.5;
  c.inflation_radius = 0.3;
  c.max_extent_m = 7.0;
  OccupancyGrid g = make(c);
  std::vector<uint8_t> mirror(g.classes().begin(), g.classes().end());
  EncodedTiles encoded;
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> x(0.05, 6.95), y(0.05, 4.45);
  for (int step = 0; step < 100; ++step) {
    ASSERT_TRUE(shoot(g, {x(rng), y(rng)}, {{x(rng), y(rng)}, {x(rng), y(rng)}}, {{x(rng), y(rng)}}).is_ok());
    encode_tiles(g.classes(), g.dirty_tiles(), encoded);
    g.clear_dirty();
    const TilePatchView view{static_cast<uint32_t>(kGridTileSide), static_cast<uint8_t>(encoded.encoding),
                             encoded.tiles, encoded.data};
    ASSERT_TRUE(apply_tiles(view, mirror, g.width(), g.height()));
    ASSERT_EQ(mirror, std::vector<uint8_t>(g.classes().begin(), g.classes().end())) << "step " << step;
  }
}

TEST(OccupancyGrid, PriorImportAndExport) {
  OccupancyGrid g = make();
  MapImage img;
  img.width = 4;
  img.height = 2;
  img.resolution = 0.5;
  img.origin_x = 2.0;
  img.origin_y = 2.0;
  // Row 0 (bottom, y in [2, 2.5)): free free occupied occupied; row 1 unknown.
  img.cells = {kMapFree, kMapFree, kMapOccupied, kMapOccupied, 0, 0, 0, 0};
  auto set = g.apply_prior(img);
  ASSERT_TRUE(set.is_ok()) << set.message();
  EXPECT_EQ(*set, 0);  // cell centres (2.5, 2.5) and (3.5, 2.5) sample the unknown upper row
  EXPECT_EQ(state(g, 2, 2), kCellUnknown);
  MapImage img2 = img;
  img2.origin_y = 2.25;  // now the bottom row covers cell centres y = 2.5
  ASSERT_TRUE(g.apply_prior(img2).is_ok());
  EXPECT_EQ(state(g, 2, 2), kCellFree);
  EXPECT_EQ(state(g, 3, 2), kCellOccupied);
  EXPECT_EQ(g.log_odds(3, 2), g.config().log_odds.prior_occupied);
  ASSERT_TRUE(g.obstruct(7.5, 7.5).is_ok());
  const MapImage out = g.to_map_image();
  EXPECT_EQ(out.width, 10u);
  EXPECT_EQ(out.cells[2 * 10 + 3], kMapOccupied);
  EXPECT_EQ(out.cells[2 * 10 + 2], kMapFree);
  EXPECT_EQ(out.cells[7 * 10 + 7], kMapOccupied);
  EXPECT_EQ(out.cells[0], kMapUnknown);
  MapImage bad = img;
  bad.cells.pop_back();
  EXPECT_FALSE(g.apply_prior(bad).is_ok());
}

}  // namespace
}  // namespace slam::mapper
