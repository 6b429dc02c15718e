// RebuildWorker: rebuilds off the caller's thread and hands the grid back once.
#include "mapper/core/rebuild_worker.hpp"

#include <gtest/gtest.h>

#include <atomic>

#include "mapper/core/map_files.hpp"
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

}  // namespace
}  // namespace slam::mapper
