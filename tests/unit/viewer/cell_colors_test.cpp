// Colour mapping of cell octets (state bits and flags) and robot colours.
#include "viewer/core/cell_colors.hpp"

#include <gtest/gtest.h>

namespace slam::viewer {
namespace {

float brightness(const Rgba& c) {
  return (c.r + c.g + c.b) / 3.0f;
}

TEST(CellColors, StatesMapToTheirColours) {
  const GridColors c;
  EXPECT_EQ(cell_color(kCellUnknown, c), c.unknown);
  EXPECT_EQ(cell_color(kCellFree, c), c.free);
  EXPECT_EQ(cell_color(kCellOccupied, c), c.occupied);
  EXPECT_EQ(cell_color(3, c), c.unknown);  // unused state value
  EXPECT_GT(brightness(cell_color(kCellFree, c)), 0.8f);
  EXPECT_LT(brightness(cell_color(kCellOccupied, c)), 0.2f);
}

TEST(CellColors, ObstructedWinsOverState) {
  const GridColors c;
  EXPECT_EQ(cell_color(kCellObstructed | kCellFree, c), c.obstructed);
  EXPECT_EQ(cell_color(kCellObstructed | kCellOccupied | kCellInflated, c), c.obstructed);
}

TEST(CellColors, InflationTintsFreeButNotOccupied) {
  GridColors c;
  const Rgba tinted = cell_color(kCellFree | kCellInflated, c);
  EXPECT_NE(tinted, c.free);
  EXPECT_EQ(cell_color(kCellOccupied | kCellInflated, c), c.occupied);
  c.show_inflation = false;
  EXPECT_EQ(cell_color(kCellFree | kCellInflated, c), c.free);
}

TEST(CellColors, AlphaScalesEveryCell) {
  GridColors c;
  c.alpha = 0.5f;
  EXPECT_FLOAT_EQ(cell_color(kCellFree, c).a, 0.5f);
  EXPECT_FLOAT_EQ(cell_color(kCellObstructed, c).a, 0.5f);
}

TEST(CellColors, PaletteMatchesCellColorForEveryLowNibble) {
  const GridColors c;
  const auto p = cell_palette(c);
  for (unsigned v = 0; v < 16; ++v) EXPECT_EQ(p[v], cell_color(static_cast<uint8_t>(v), c)) << v;
  // Higher bits are ignored by the mapping (the shader masks with 15 too).
  EXPECT_EQ(cell_color(0x10 | kCellFree, c), cell_color(kCellFree, c));
}

TEST(CellColors, RobotColourIsStablePerId) {
  EXPECT_EQ(default_robot_color("robot1"), default_robot_color("robot1"));
  EXPECT_FLOAT_EQ(default_robot_color("x").a, 1.0f);
}

}  // namespace
}  // namespace slam::viewer
