// Rebuild from the store: same config reproduces the live grid, a new resolution works, obstructions
// and the prior survive, a reset robot's data disappears, and a bad config changes nothing.
#include "mapper/core/rebuild.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "temp_dir.hpp"

namespace slam::mapper {
namespace {

GridConfig config() {
  GridConfig c;
  c.resolution = 0.1;
  c.origin_x = -2.0;
  c.origin_y = -2.0;
  c.width_m = 4.0;
  c.height_m = 4.0;
  c.inflation_radius = 0.2;
  c.max_extent_m = 40.0;
  c.grow_chunk_m = 2.0;
  return c;
}

// Feeds a few robots' scans of a square room to both the live grid and the store.
void feed(OccupancyGrid& grid, ObservationStore& store) {
  for (int step = 0; step < 40; ++step) {
    const double rx = -1.0 + 0.05 * step;
    const double ry = 0.2 * (step % 3);
    std::vector<Vec2> hits;
    std::vector<Vec2> misses;
    for (int k = 0; k < 12; ++k) {
      const double wall = 3.0;
      if (k % 4 == 0)
        hits.push_back({wall, ry + 0.3 * (k - 6)});
      else if (k % 4 == 1)
        hits.push_back({rx + 0.3 * (k - 6), wall});
      else if (k % 4 == 2)
        hits.push_back({-wall, ry - 0.2 * k});
      else
        misses.push_back({rx + 0.1 * k, -2.9});
    }
    ObservationView v{rx, ry, 0.0, false, hits, misses};
    ASSERT_TRUE(grid.integrate(v).is_ok());
    ASSERT_TRUE(store.append(step % 2 ? "odd" : "even", static_cast<uint64_t>(step), step, 0, v).is_ok());
  }
}

TEST(Rebuild, SameConfigReproducesTheLiveGrid) {
  testkit::TempDir dir("mapper");
  auto store = ObservationStore::open(dir.path() / "m.db");
  ASSERT_TRUE(store.is_ok());
  auto live = OccupancyGrid::create(config());
  ASSERT_TRUE(live.is_ok());
  feed(*live, *store);
  ASSERT_TRUE(live->obstruct(0.55, 0.55).is_ok());
  ASSERT_TRUE(store->add_obstruction({0.55, 0.55}).is_ok());
  RebuildStats stats;
  auto rebuilt = rebuild_grid(config(), *store, &stats);
  ASSERT_TRUE(rebuilt.is_ok()) << rebuilt.message();
  EXPECT_EQ(stats.observations, 40);
  EXPECT_EQ(stats.rejected, 0);
  EXPECT_EQ(stats.obstructions, 1);
  EXPECT_EQ(rebuilt->width(), live->width());
  EXPECT_EQ(rebuilt->height(), live->height());
  EXPECT_DOUBLE_EQ(rebuilt->origin_x(), live->origin_x());
  EXPECT_TRUE(std::equal(rebuilt->classes().begin(), rebuilt->classes().end(), live->classes().begin(),
                         live->classes().end()));
}

TEST(Rebuild, ManyBatchesReproduceTheLiveGridInOrder) {
  // Several thousand observations cross the reader/integrator hand-off in many batches; clamped
  // log-odds depend on order, so any reordering would show up as a different grid.
  testkit::TempDir dir("mapper");
  auto store = ObservationStore::open(dir.path() / "m.db");
  ASSERT_TRUE(store.is_ok());
  auto live = OccupancyGrid::create(config());
  ASSERT_TRUE(live.is_ok());
  for (int round = 0; round < 150; ++round) feed(*live, *store);
  ASSERT_TRUE(store->flush().is_ok());
  RebuildStats stats;
  auto rebuilt = rebuild_grid(config(), *store, &stats);
  ASSERT_TRUE(rebuilt.is_ok()) << rebuilt.message();
  EXPECT_EQ(stats.observations, 150 * 40);
  EXPECT_TRUE(std::equal(rebuilt->classes().begin(), rebuilt->classes().end(), live->classes().begin(),
                         live->classes().end()));
}

TEST(Rebuild, NewResolutionKeepsObstructionsAndPrior) {
  testkit::TempDir dir("mapper");
  auto store = ObservationStore::open(dir.path() / "m.db");
  ASSERT_TRUE(store.is_ok());
  auto live = OccupancyGrid::create(config());
  ASSERT_TRUE(live.is_ok());
  feed(*live, *store);
  ASSERT_TRUE(store->add_obstruction({0.55, 0.55}).is_ok());
  MapImage prior;
  prior.width = prior.height = 2;
  prior.resolution = 1.0;
  prior.origin_x = -10.0;
  prior.origin_y = -10.0;
  prior.cells = {kMapOccupied, kMapOccupied, kMapOccupied, kMapOccupied};
  ASSERT_TRUE(store->save_prior(prior).is_ok());

  GridConfig coarse = config();
  coarse.resolution = 0.25;
  RebuildStats stats;
  auto g = rebuild_grid(coarse, *store, &stats);
  ASSERT_TRUE(g.is_ok()) << g.message();
  EXPECT_EQ(stats.observations, 40);
  EXPECT_GT(stats.prior_cells, 0);
  std::optional<Cell> c;
  c = g->cell_at({0.55, 0.55});
  ASSERT_TRUE(c);
  EXPECT_TRUE(g->cell_class(c->x, c->y) & kCellObstructed);
  c = g->cell_at({3.1, -0.55});  // the wall at x = 3 (hits at y = -0.6)
  ASSERT_TRUE(c);
  EXPECT_EQ(g->cell_class(c->x, c->y) & kCellStateMask, kCellOccupied);
  c = g->cell_at({-9.5, -9.5});  // grew to hold the prior
  ASSERT_TRUE(c);
  EXPECT_EQ(g->cell_class(c->x, c->y) & kCellStateMask, kCellOccupied);
}

TEST(Rebuild, ResetRobotRemovesItsData) {
  testkit::TempDir dir("mapper");
  auto store = ObservationStore::open(dir.path() / "m.db");
  ASSERT_TRUE(store.is_ok());
  auto live = OccupancyGrid::create(config());
  ASSERT_TRUE(live.is_ok());
  feed(*live, *store);
  ASSERT_EQ(*store->delete_robot("odd"), 20);
  RebuildStats stats;
  auto g = rebuild_grid(config(), *store, &stats);
  ASSERT_TRUE(g.is_ok());
  EXPECT_EQ(stats.observations, 20);
}

TEST(Rebuild, BadConfigIsAnError) {
  testkit::TempDir dir("mapper");
  auto store = ObservationStore::open(dir.path() / "m.db");
  ASSERT_TRUE(store.is_ok());
  GridConfig bad = config();
  bad.resolution = -1.0;
  auto g = rebuild_grid(bad, *store);
  ASSERT_FALSE(g.is_ok());
  EXPECT_NE(g.message().find("resolution"), std::string::npos);
}

}  // namespace
}  // namespace slam::mapper
