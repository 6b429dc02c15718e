// Point store: append, bounds, last-N ranges, reset generation, and the per-robot cap.
#include "viewer/core/point_store.hpp"

#include <gtest/gtest.h>

#include "viewer/core/robot_registry.hpp"

namespace slam::viewer {
namespace {

TEST(PointStore, AppendsAndTracksBounds) {
  PointStore s;
  const float a[] = {1.0f, 2.0f, -3.0f, 4.0f};
  EXPECT_EQ(s.append(a, 2), 2u);
  EXPECT_EQ(s.size(), 2u);
  EXPECT_FLOAT_EQ(s.data()[2], -3.0f);
  EXPECT_DOUBLE_EQ(s.bounds().min_x, -3.0);
  EXPECT_DOUBLE_EQ(s.bounds().max_y, 4.0);
}

TEST(PointStore, LastNSelectsNewest) {
  PointStore s;
  std::vector<float> xy(200);
  s.append(xy.data(), 100);
  auto r = s.last_n(10);
  EXPECT_EQ(r.first, 90u);
  EXPECT_EQ(r.count, 10u);
  r = s.last_n(0);
  EXPECT_EQ(r.first, 0u);
  EXPECT_EQ(r.count, 100u);
  r = s.last_n(1000);
  EXPECT_EQ(r.count, 100u);
}

TEST(PointStore, ResetClearsAndBumpsGeneration) {
  PointStore s;
  const float a[] = {1.0f, 2.0f};
  s.append(a, 1);
  const uint64_t g = s.generation();
  s.reset();
  EXPECT_TRUE(s.empty());
  EXPECT_GT(s.generation(), g);
  s.append(a, 1);
  EXPECT_EQ(s.size(), 1u);
}

TEST(PointStore, CapDropsAndCounts) {
  PointStore s(3);
  std::vector<float> xy(10, 0.5f);
  EXPECT_EQ(s.append(xy.data(), 5), 3u);
  EXPECT_EQ(s.dropped(), 2u);
  EXPECT_EQ(s.append(xy.data(), 1), 0u);
  EXPECT_EQ(s.dropped(), 3u);
}

TEST(RobotRegistry, ObservationsFeedPointsAndStateMarksOnline) {
  RobotRegistry reg;
  reg.defaults().point_radius_px = 4.0f;
  ObservationData o{"r1", 1, {1.0, 1.0, 0.0}, {2.0f, 3.0f, 4.0f, 5.0f}};
  reg.ingest(o);
  msg::RobotState st;
  st.robot_id = "r1";
  st.online = true;
  reg.ingest(std::move(st));
  ASSERT_EQ(reg.size(), 1u);
  EXPECT_EQ(reg.at(0).points.size(), 2u);
  EXPECT_FLOAT_EQ(reg.at(0).settings.point_radius_px, 4.0f);
  EXPECT_EQ(reg.at(0).settings.color.r, default_robot_color("r1").r);
  EXPECT_EQ(reg.online(), 1u);
  EXPECT_EQ(reg.total_points(), 2u);
  WorldBox b;
  ASSERT_TRUE(reg.bounds(&b));
  EXPECT_DOUBLE_EQ(b.max_x, 4.0);
}

}  // namespace
}  // namespace slam::viewer
