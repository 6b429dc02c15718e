// RebuildWorker: rebuilds off the caller's thread and hands the grid back once; a partial re-render
// hands back its tiles and the index its full rebuild built.
#include "mapper/core/rebuild_worker.hpp"

#include <gtest/gtest.h>

#include <atomic>

#include "mapper/core/map_files.hpp"
#include "mapper/core/partial_rerender.hpp"
#include "mapper_test_data.hpp"
#include "temp_dir.hpp"

namespace slam::mapper {
namespace {

using test_data::feed;
using test_data::small;

TEST(RebuildWorker, RebuildsOffThreadAndHandsTheGridBackOnce) {
  testkit::TempDir dir("mapper");
  const auto path = dir.path() / "map.db";
  auto store = open_store(path);
  ASSERT_TRUE(store);
  auto live = OccupancyGrid::create(small());
  feed(*live, *store);

  std::atomic<int> done{0};
  RebuildWorker worker([&] { ++done; });
  GridConfig finer = small();
  finer.resolution = 0.05;
  ASSERT_TRUE(worker.start(finer, path));
  EXPECT_TRUE(worker.busy());
  EXPECT_FALSE(worker.start(finer, path)) << "one rebuild at a time";
  auto outcome = worker.wait();
  ASSERT_TRUE(outcome);
  ASSERT_TRUE(outcome->grid) << outcome->grid.message();
  EXPECT_EQ(outcome->stats.observations, 1);
  EXPECT_DOUBLE_EQ(outcome->grid->resolution(), 0.05);
  const std::optional<Cell> c = outcome->grid->cell_at({1.03, 0.03});
  ASSERT_TRUE(c);
  EXPECT_EQ(outcome->grid->cell_class(c->x, c->y) & kCellStateMask, kCellOccupied);
  EXPECT_EQ(done.load(), 1);
  EXPECT_FALSE(worker.busy());
  EXPECT_FALSE(worker.take()) << "handed back once";

  ASSERT_TRUE(worker.start(finer, dir.path() / "no-such-dir" / "map.db"));
  auto failed = worker.wait();
  ASSERT_TRUE(failed);
  EXPECT_FALSE(failed->grid) << "an unreadable store is an error, not an empty map";
}

TEST(RebuildWorker, APartialRerenderHandsBackItsTiles) {
  testkit::TempDir dir("mapper");
  const auto path = dir.path() / "map.db";
  auto store = open_store(path);
  ASSERT_TRUE(store);
  auto live = OccupancyGrid::create(small());
  feed(*live, *store);

  RebuildWorker worker([] {});
  ASSERT_TRUE(worker.start(small(), path));
  auto full = worker.wait();
  ASSERT_TRUE(full && full->grid);
  EXPECT_EQ(full->index.observations(), 1);
  EXPECT_FALSE(full->partial);

  RerenderPlan plan;  // redraws the tile of the wall, from the one stored observation
  plan.geometry = full->grid->geometry();
  plan.config = small();
  plan.layout_version = full->grid->layout_version();
  const Cell wall = *full->grid->cell_at({1.03, 0.03});
  plan.tiles = {TileLayout{plan.geometry.width, plan.geometry.height, kGridTileSide}.tile_of(wall.x, wall.y)};
  plan.replays = {RerenderPlan::Replay{0, 1, 1, Pose{}, 0, false}};
  ASSERT_TRUE(worker.start_partial(plan, path));
  EXPECT_TRUE(worker.busy());
  auto partial = worker.wait();
  ASSERT_TRUE(partial && partial->partial);
  ASSERT_TRUE(*partial->partial) << partial->partial->message();
  EXPECT_EQ((*partial->partial)->replayed, 1);
  EXPECT_EQ((*partial->partial)->plan.tiles, plan.tiles);
}

}  // namespace
}  // namespace slam::mapper
