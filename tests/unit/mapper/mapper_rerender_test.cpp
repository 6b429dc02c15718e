// Mapper re-renders (mapper_rerender.cpp): observations arriving while a partial re-render runs are
// drawn into the redrawn tiles and stored; a move beyond the grid re-renders fully; the footprint
// index follows every path (live, partial, full, restart).
#include <gtest/gtest.h>

#include <vector>

#include "mapper/core/mapper.hpp"
#include "mapper/core/rebuild.hpp"
#include "mapper_test_data.hpp"
#include "temp_dir.hpp"

namespace slam::mapper {
namespace {

class MapperRerender : public ::testing::Test {
 protected:
  MapperRerender() {
    options_.store = (dir_.path() / "map.db").string();
    options_.grid = test_data::small();
    options_.grid.width_m = 8.0;
    options_.grid.origin_x = -4.0;
    options_.robot_filter.radius_m = 0.0;
  }

  std::unique_ptr<Mapper> make() {
    auto mapper = Mapper::create(options_, counters_, 1, [] {});
    EXPECT_TRUE(mapper.is_ok()) << mapper.message();
    return mapper ? std::move(*mapper) : nullptr;
  }

  // Robot r1 at (x, 0) seeing a wall 1.2 m east and a free ray west, odometry frame.
  static ObservationView scan(double x, std::vector<Vec2>& hits, std::vector<Vec2>& misses) {
    hits.clear();
    misses.clear();
    for (int k = -3; k <= 3; ++k) hits.push_back({x + 1.2, 0.1 * k + 0.03});
    misses.push_back({x - 1.5, 0.2});
    return ObservationView{x, 0.0, 0.0, false, hits, misses};
  }

  static void feed(Mapper& mapper, uint64_t seq, double x, KeyframeId kf, const Pose& correction) {
    std::vector<Vec2> hits, misses;
    mapper.integrate(RobotScan{"r1", seq, 0, scan(x, hits, misses), kf, correction}, 0);
  }

  // A full rebuild of the store with the mapper's corrections.
  OccupancyGrid full_rebuild(const Mapper& mapper) {
    auto store = ObservationStore::open(options_.store);
    EXPECT_TRUE(store.is_ok());
    auto grid = rebuild_grid(mapper.grid().config(), *store, nullptr, mapper.corrections());
    EXPECT_TRUE(grid.is_ok()) << grid.message();
    return std::move(*grid);
  }

  testkit::TempDir dir_{"mapper-rerender"};
  MapperOptions options_;
  Counters counters_;
};

TEST_F(MapperRerender, ObservationsArrivingMeanwhileAreDrawnIntoTheRedrawnTilesAndStored) {
  auto mapper = make();
  const std::vector<Keyframe> first{{1, "r1", 0, Pose{}, Pose{}}, {2, "r1", 0, Pose{2.0, 0, 0}, Pose{}}};
  ASSERT_TRUE(mapper->save_keyframes(first));
  for (uint64_t i = 0; i < 4; ++i) feed(*mapper, i + 1, -2.0 + 0.1 * static_cast<double>(i), 1, Pose{});
  for (uint64_t i = 0; i < 4; ++i) feed(*mapper, i + 5, 1.0 + 0.1 * static_cast<double>(i), 2, Pose{});
  EXPECT_EQ(mapper->footprints().observations(), 8);

  const std::vector<Keyframe> moved{{1, "r1", 0, Pose{}, Pose{0.15, 0.1, 0.03}}};
  ASSERT_TRUE(mapper->save_keyframes(moved));
  mapper->rerender();
  ASSERT_TRUE(mapper->rebuilding());
  // Keyframe 3 arrives while the tiles are drawn: on top of the old wall of keyframe 1 and elsewhere.
  const std::vector<Keyframe> third{{3, "r1", 0, Pose{}, Pose{0.0, 0.2, 0.0}}};
  ASSERT_TRUE(mapper->save_keyframes(third));
  feed(*mapper, 9, -2.0, 3, Pose{0.0, 0.2, 0.0});
  feed(*mapper, 10, 1.5, 3, Pose{0.0, 0.2, 0.0});
  mapper->wait_for_rebuild();
  EXPECT_FALSE(mapper->take_swapped());
  EXPECT_EQ(counters_.get("rerenders_partial").load(), 1);
  EXPECT_EQ(mapper->footprints().observations(), 10);
  mapper->commit();
  const OccupancyGrid expected = full_rebuild(*mapper);
  EXPECT_TRUE(test_data::same_grid(mapper->grid(), expected));

  // Moved back: only keyframe 1's tiles again; still what a full rebuild gives, and after a restart.
  const std::vector<Keyframe> back{{1, "r1", 0, Pose{}, Pose{}}};
  ASSERT_TRUE(mapper->save_keyframes(back));
  mapper->rerender();
  mapper->wait_for_rebuild();
  EXPECT_EQ(counters_.get("rerenders_partial").load(), 2);
  EXPECT_TRUE(test_data::same_grid(mapper->grid(), full_rebuild(*mapper)));
  const OccupancyGrid before_restart = mapper->grid();
  mapper.reset();
  auto restarted = make();
  EXPECT_TRUE(test_data::same_grid(restarted->grid(), before_restart));
  EXPECT_EQ(restarted->footprints().observations(), 10);
}

TEST_F(MapperRerender, AMoveBeyondTheGridRerendersFullyAndTheGridGrows) {
  auto mapper = make();
  const std::vector<Keyframe> first{{1, "r1", 0, Pose{}, Pose{}}};
  ASSERT_TRUE(mapper->save_keyframes(first));
  for (uint64_t i = 0; i < 3; ++i) feed(*mapper, i + 1, 0.1 * static_cast<double>(i), 1, Pose{});
  const int32_t width = mapper->grid().width();
  const std::vector<Keyframe> moved{{1, "r1", 0, Pose{}, Pose{3.5, 0.0, 0.0}}};  // the wall lands at x = 4.7
  ASSERT_TRUE(mapper->save_keyframes(moved));
  mapper->rerender();
  mapper->wait_for_rebuild();
  EXPECT_TRUE(mapper->take_swapped());  // a new grid: a snapshot
  EXPECT_EQ(counters_.get("rerenders_partial").load(), 0);
  EXPECT_EQ(counters_.get("rerender_observations").load(), 3);
  EXPECT_GT(mapper->grid().width(), width);
  mapper->commit();
  EXPECT_TRUE(test_data::same_grid(mapper->grid(), full_rebuild(*mapper)));
  EXPECT_EQ(mapper->footprints().observations(), 3);
}

TEST_F(MapperRerender, ASubCellMoveStartsNothing) {
  auto mapper = make();
  const std::vector<Keyframe> first{{1, "r1", 0, Pose{}, Pose{}}};
  ASSERT_TRUE(mapper->save_keyframes(first));
  feed(*mapper, 1, 0.0, 1, Pose{});
  const std::vector<Keyframe> moved{{1, "r1", 0, Pose{}, Pose{0.01, 0.0, 0.0}}};  // a tenth of a cell
  ASSERT_TRUE(mapper->save_keyframes(moved));
  mapper->rerender();
  EXPECT_FALSE(mapper->rebuilding());
  EXPECT_EQ(counters_.get("rerender_observations").load(), 0);
}

}  // namespace
}  // namespace slam::mapper
