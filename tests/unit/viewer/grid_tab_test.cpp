// GridTab: the layout request starts from the first grid seen, "apply" sends it as GridConfig,
// values the mapper would refuse show an error and send nothing, and "clear manual obstructions"
// sends its MapEdit.
#include "viewer/core/grid_tab.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "fake_command_sink.hpp"

namespace slam::viewer {
namespace {

msg::GridSnapshot snapshot(uint32_t w, uint32_t h, double resolution, Vec2 origin, double inflation) {
  msg::GridSnapshot s;
  s.layout_id = 1;
  s.version = 1;
  s.info = {w, h, resolution, origin, inflation};
  s.cells.assign(static_cast<size_t>(w) * h, 0);
  return s;
}

class GridTabTest : public ::testing::Test {
 protected:
  void expect_refused() {
    EXPECT_EQ(sink.total(), 0u);
    EXPECT_FALSE(tab.error.empty());
  }
  ViewerState state{100};
  FakeCommandSink sink;
  GridTab tab;
};

TEST_F(GridTabTest, RequestStartsFromTheFirstGridOnly) {
  tab.adopt(state.grid);  // no grid yet: the defaults stay
  EXPECT_FALSE(tab.initialised);
  ASSERT_TRUE(state.grid.apply_snapshot(snapshot(200, 100, 0.1, {-5.0, -2.0}, 0.3)));
  tab.adopt(state.grid);
  EXPECT_TRUE(tab.initialised);
  EXPECT_DOUBLE_EQ(tab.request.resolution, 0.1);
  EXPECT_DOUBLE_EQ(tab.request.origin.x, -5.0);
  EXPECT_DOUBLE_EQ(tab.request.origin.y, -2.0);
  EXPECT_DOUBLE_EQ(tab.request.width_m, 20.0);
  EXPECT_DOUBLE_EQ(tab.request.height_m, 10.0);
  EXPECT_DOUBLE_EQ(tab.request.inflation_radius, 0.3);

  tab.request.resolution = 0.05;  // the operator's edit survives the next grid
  ASSERT_TRUE(state.grid.apply_snapshot(snapshot(10, 10, 0.2, {}, 0.0)));
  tab.adopt(state.grid);
  EXPECT_DOUBLE_EQ(tab.request.resolution, 0.05);
}

TEST_F(GridTabTest, ApplySendsResolutionExtentInflationAndLegacyMode) {
  tab.request = GridConfigCommand{0.025, {-1.0, 2.0}, 30.0, 40.0, 0.5, true};
  tab.apply(state, sink);
  ASSERT_EQ(sink.grid_configs.size(), 1u);
  const GridConfigCommand& c = sink.grid_configs[0];
  EXPECT_DOUBLE_EQ(c.resolution, 0.025);
  EXPECT_DOUBLE_EQ(c.origin.x, -1.0);
  EXPECT_DOUBLE_EQ(c.origin.y, 2.0);
  EXPECT_DOUBLE_EQ(c.width_m, 30.0);
  EXPECT_DOUBLE_EQ(c.height_m, 40.0);
  EXPECT_DOUBLE_EQ(c.inflation_radius, 0.5);
  EXPECT_TRUE(c.legacy_mode);
  EXPECT_TRUE(tab.error.empty());
  EXPECT_NE(state.status_line.find("grid config"), std::string::npos);
}

TEST_F(GridTabTest, ZeroInflationIsAllowed) {
  tab.request.inflation_radius = 0.0;
  tab.apply(state, sink);
  EXPECT_EQ(sink.grid_configs.size(), 1u);
}

TEST_F(GridTabTest, ResolutionOutOfRangeIsRefused) {
  for (double r : {0.0, -0.05, 0.0005, std::nan("")}) {
    tab.request.resolution = r;
    tab.apply(state, sink);
  }
  expect_refused();
}

TEST_F(GridTabTest, ExtentOutOfRangeIsRefused) {
  tab.request.width_m = 0.0;
  tab.apply(state, sink);
  tab.request.width_m = 10.0;
  tab.request.height_m = -1.0;
  tab.apply(state, sink);
  tab.request.height_m = 10.0;
  tab.request.origin.x = 2e6;
  tab.apply(state, sink);
  tab.request.origin.x = 0.0;
  tab.request.origin.y = INFINITY;
  tab.apply(state, sink);
  expect_refused();
}

TEST_F(GridTabTest, NegativeInflationIsRefused) {
  tab.request.inflation_radius = -0.1;
  tab.apply(state, sink);
  expect_refused();
}

TEST_F(GridTabTest, ClearObstructionsSendsItsMapEdit) {
  tab.clear_obstructions(state, sink);
  ASSERT_EQ(sink.edits.size(), 1u);
  EXPECT_EQ(sink.edits[0].kind, MapEditKind::ClearObstructions);
}

TEST_F(GridTabTest, RefusedSendShowsAnError) {
  sink.refuse = true;
  tab.apply(state, sink);
  EXPECT_NE(tab.error.find("NOT sent"), std::string::npos);
}

}  // namespace
}  // namespace slam::viewer
