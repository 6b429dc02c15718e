// The automatic fit: the grid's extent while nothing is mapped, then the content (padded, with
// room to grow), again when the content outgrows the box, the grid is re-laid out or the window
// resized; never after the operator moved the view.
#include "viewer/core/auto_fit.hpp"

#include <gtest/gtest.h>

namespace slam::viewer {
namespace {

const Viewport kWindow{420.0, 0.0, 860.0, 800.0};
const WorldBox kGrid{-10.0, -10.0, 10.0, 10.0};

TEST(AutoFit, NothingToFitBeforeAnyData) {
  AutoFit fit;
  EXPECT_FALSE(fit.update(std::nullopt, std::nullopt, 0, kWindow, false));
}

TEST(AutoFit, TheGridExtentUntilSomethingIsMappedThenTheContentPadded) {
  AutoFit fit;
  auto box = fit.update(std::nullopt, kGrid, 1, kWindow, false);
  ASSERT_TRUE(box);
  EXPECT_DOUBLE_EQ(box->min_x, -10.0);
  EXPECT_DOUBLE_EQ(box->max_y, 10.0);
  EXPECT_FALSE(fit.update(std::nullopt, kGrid, 1, kWindow, false));
  // Content inside the extent still re-fits: the mapped part is what matters. 8 m wide gets 10 %
  // slack per side; 4 m high is first raised to kMinSide (6 m).
  box = fit.update(WorldBox{0.0, 0.0, 8.0, 4.0}, kGrid, 1, kWindow, false);
  ASSERT_TRUE(box);
  EXPECT_NEAR(box->min_x, -0.8, 1e-9);
  EXPECT_NEAR(box->max_x, 8.8, 1e-9);
  EXPECT_NEAR(box->min_y, 2.0 - 3.6, 1e-9);
  EXPECT_NEAR(box->max_y, 2.0 + 3.6, 1e-9);
}

TEST(AutoFit, ALoneRobotIsNotZoomedIntoADot) {
  AutoFit fit;
  auto box = fit.update(WorldBox{1.0, 1.0, 1.0, 1.0}, std::nullopt, 0, kWindow, false);
  ASSERT_TRUE(box);
  EXPECT_GE(box->max_x - box->min_x, AutoFit::kMinSide);
  EXPECT_DOUBLE_EQ((box->min_y + box->max_y) / 2.0, 1.0);
}

TEST(AutoFit, GrowingContentRefitsOnlyWhenItLeavesTheBox) {
  AutoFit fit;
  ASSERT_TRUE(fit.update(WorldBox{0.0, 0.0, 10.0, 10.0}, kGrid, 1, kWindow, false));
  EXPECT_FALSE(fit.update(WorldBox{0.0, 0.0, 10.5, 10.5}, kGrid, 1, kWindow, false));
  auto box = fit.update(WorldBox{0.0, 0.0, 14.0, 10.5}, kGrid, 1, kWindow, false);
  ASSERT_TRUE(box);
  EXPECT_GE(box->max_x, 14.0);
}

TEST(AutoFit, ARelaidGridOrAResizedWindowRefits) {
  AutoFit fit;
  const WorldBox content{0.0, 0.0, 5.0, 5.0};
  ASSERT_TRUE(fit.update(content, kGrid, 1, kWindow, false));
  EXPECT_FALSE(fit.update(content, kGrid, 1, kWindow, false));
  EXPECT_TRUE(fit.update(content, WorldBox{-10.0, -10.0, 20.0, 10.0}, 2, kWindow, false));
  EXPECT_FALSE(fit.update(content, WorldBox{-10.0, -10.0, 20.0, 10.0}, 2, kWindow, false));
  EXPECT_TRUE(fit.update(content, WorldBox{-10.0, -10.0, 20.0, 10.0}, 2, Viewport{420.0, 0.0, 1500.0, 1000.0},
                         false));
}

TEST(AutoFit, NeverAfterTheOperatorMovedTheView) {
  AutoFit fit;
  ASSERT_TRUE(fit.update(WorldBox{0.0, 0.0, 1.0, 1.0}, std::nullopt, 0, kWindow, false));
  EXPECT_FALSE(fit.update(WorldBox{0.0, 0.0, 50.0, 1.0}, kGrid, 1, kWindow, true));
  EXPECT_FALSE(fit.update(WorldBox{0.0, 0.0, 90.0, 1.0}, kGrid, 2, kWindow, true));
}

TEST(AutoFit, UniteHoldsBothBoxes) {
  const WorldBox u = unite({0.0, 1.0, 2.0, 3.0}, {-1.0, 2.0, 1.0, 5.0});
  EXPECT_DOUBLE_EQ(u.min_x, -1.0);
  EXPECT_DOUBLE_EQ(u.min_y, 1.0);
  EXPECT_DOUBLE_EQ(u.max_x, 2.0);
  EXPECT_DOUBLE_EQ(u.max_y, 5.0);
}

}  // namespace
}  // namespace slam::viewer
