// FrontierMap: which cells are frontiers, incremental updates equal a rebuild, clustering.
#include "planner/core/frontiers.hpp"

#include <gtest/gtest.h>

#include <random>

#include "grid_builder.hpp"

namespace slam::planner {
namespace {

TEST(Frontiers, FreeCellsNextToUnknown) {
  const PlanningGrid g = test::grid_from_art({
      "????",
      "..i?",
      "#...",
  });
  FrontierMap f;
  f.rebuild(g);
  EXPECT_TRUE(f.is_frontier({0, 1}, g));
  EXPECT_TRUE(f.is_frontier({1, 1}, g));
  EXPECT_FALSE(f.is_frontier({2, 1}, g));  // inflated: a robot cannot stand there
  EXPECT_TRUE(f.is_frontier({3, 0}, g));   // unknown above
  EXPECT_FALSE(f.is_frontier({2, 0}, g));  // only a diagonal unknown neighbour
  EXPECT_FALSE(f.is_frontier({0, 0}, g));  // occupied
  EXPECT_EQ(f.count(), 3u);
}

TEST(Frontiers, IncrementalUpdateMatchesRebuild) {
  std::mt19937 rng(11);
  PlanningGrid g = test::uniform_grid(50, 40, kCellUnknown);
  FrontierMap incremental;
  incremental.rebuild(g);
  for (int step = 0; step < 200; ++step) {
    const CellBox box{static_cast<int32_t>(rng() % 45), static_cast<int32_t>(rng() % 35),
                      1 + static_cast<int32_t>(rng() % 5), 1 + static_cast<int32_t>(rng() % 5)};
    for (int32_t y = box.y0; y < box.y0 + box.height; ++y)
      for (int32_t x = box.x0; x < box.x0 + box.width; ++x)
        g.set({x, y}, static_cast<uint8_t>(rng() % 100 < 70 ? kCellFree : rng() % 3));
    incremental.update(g, box);
  }
  FrontierMap full;
  full.rebuild(g);
  EXPECT_EQ(incremental.count(), full.count());
  for (int32_t y = 0; y < g.height(); ++y) {
    for (int32_t x = 0; x < g.width(); ++x) {
      ASSERT_EQ(incremental.is_frontier({x, y}, g), full.is_frontier({x, y}, g)) << x << "," << y;
    }
  }
}

TEST(Frontiers, ClustersEightConnectedAndDropsSmallOnes) {
  const PlanningGrid g = test::grid_from_art({
      "??????????",
      ".....#####",
      "##########",
      "#.?#######",
      "##########",
  });
  FrontierMap f;
  f.rebuild(g);
  std::vector<FrontierCluster> clusters;
  f.cluster(g, 1, clusters);
  ASSERT_EQ(clusters.size(), 2u);
  f.cluster(g, 2, clusters);
  ASSERT_EQ(clusters.size(), 1u);
  EXPECT_EQ(clusters[0].size, 5u);
  EXPECT_EQ(clusters[0].target, (Cell{2, 3}));
  EXPECT_NEAR(clusters[0].centroid.x, 2.5, 1e-9);
  EXPECT_NEAR(clusters[0].centroid.y, 3.5, 1e-9);
}

TEST(Frontiers, DiagonalNeighboursJoinOneCluster) {
  const PlanningGrid g = test::grid_from_art({
      "?#?",
      ".?#",
      "#..",
  });
  FrontierMap f;
  f.rebuild(g);
  std::vector<FrontierCluster> clusters;
  f.cluster(g, 1, clusters);
  ASSERT_EQ(clusters.size(), 1u);
  EXPECT_EQ(clusters[0].size, 2u);  // (0,1) and (1,0) touch only diagonally
}

}  // namespace
}  // namespace slam::planner
