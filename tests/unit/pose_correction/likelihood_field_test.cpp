// LikelihoodField: 1 on an occupied cell, the Gaussian of the distance beside it, 0 beyond three
// sigma and outside its box, obstructed cells count as occupied, free and unknown ones do not; an
// oversized box is refused. SearchLattice: its candidates and its outer ring.
#include "pose_correction/likelihood_field.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/core/cell_class.hpp"
#include "pose_correction/correlative_search.hpp"

namespace slam::correction {
namespace {

GridGeometry ten_by_ten() {
  GridGeometry g;
  g.resolution = 0.05;
  g.width = g.height = 10;
  return g;
}

TEST(LikelihoodField, IsTheGaussianOfTheDistanceToTheNearestOccupiedCell) {
  const GridGeometry g = ten_by_ten();
  std::vector<uint8_t> cells(g.cells(), kCellFree);
  cells[g.index({5, 5})] = kCellOccupied;
  LikelihoodField field(0.05);  // one cell
  ASSERT_TRUE(field.build(GridView{g, cells}, CellBox{0, 0, 10, 10}, 1000));
  EXPECT_FLOAT_EQ(field.at(5, 5), 1.0f);
  EXPECT_NEAR(field.at(6, 5), std::exp(-0.5), 1e-6);
  EXPECT_NEAR(field.at(6, 6), std::exp(-1.0), 1e-6);
  EXPECT_FLOAT_EQ(field.at(9, 5), 0.0f);    // four cells: beyond three sigma
  EXPECT_FLOAT_EQ(field.at(50, 50), 0.0f);  // outside the box
}

TEST(LikelihoodField, ReadsObstructedAsOccupiedAndReachesBeyondTheGrid) {
  const GridGeometry g = ten_by_ten();
  std::vector<uint8_t> cells(g.cells(), kCellUnknown);
  cells[g.index({0, 0})] = kCellFree | kCellObstructed;
  LikelihoodField field(0.05);
  ASSERT_TRUE(field.build(GridView{g, cells}, CellBox{-3, -3, 6, 6}, 1000));
  EXPECT_FLOAT_EQ(field.at(0, 0), 1.0f);
  EXPECT_NEAR(field.at(-1, 0), std::exp(-0.5), 1e-6);
  EXPECT_FLOAT_EQ(field.at(1, 2), static_cast<float>(std::exp(-2.5)));
}

TEST(LikelihoodField, RefusesABoxBeyondItsLimit) {
  const GridGeometry g = ten_by_ten();
  std::vector<uint8_t> cells(g.cells(), kCellOccupied);
  LikelihoodField field(0.05);
  EXPECT_FALSE(field.build(GridView{g, cells}, CellBox{0, 0, 100, 100}, 1000));
  EXPECT_FALSE(field.build(GridView{g, cells}, CellBox{0, 0, 0, 5}, 1000));
}

TEST(SearchLattice, CoversTheWindowInWholeCellsAndMarksItsOuterRing) {
  const SearchLattice l = SearchLattice::around(SearchWindow{0.15, 0.1}, 0.05, 5.0, 0.0, 0.0);
  EXPECT_EQ(l.step_cells, 1);
  EXPECT_EQ(l.linear_steps, 3);
  EXPECT_EQ(l.angular_steps, 10);  // 0.05 m at 5 m: 0.01 rad per step
  EXPECT_NEAR(l.angular_step, 0.01, 1e-12);
  EXPECT_EQ(l.size(), static_cast<size_t>(7 * 7 * 21));
  const size_t centre = static_cast<size_t>(10) * l.per_heading() + 3 * 7 + 3;
  EXPECT_TRUE(l.offset(centre).isZero());
  EXPECT_FALSE(l.on_edge(l.offset(centre)));
  EXPECT_TRUE(l.on_edge(l.offset(0)));
  EXPECT_NEAR(l.offset(0).x(), -0.15, 1e-12);
  EXPECT_NEAR(l.offset(0).z(), -0.1, 1e-12);
}

}  // namespace
}  // namespace slam::correction
