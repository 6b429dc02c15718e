// Robots' corrections: points stay raw (odometry frame), the robot's current correction maps them
// into the map (identity until the mapper sent one), and the fit box follows the corrected points.
#include "viewer/core/robot_registry.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace slam::viewer {
namespace {

ObservationData observation(const std::string& id, std::vector<float> xy) {
  ObservationData o;
  o.robot_id = id;
  o.hits_xy = std::move(xy);
  return o;
}

TEST(RobotRegistry, CorrectionIsIdentityUntilTheMapperSendsOne) {
  RobotRegistry robots;
  robots.ingest(observation("r1", {1.0f, 0.0f}));
  const RobotView& r = *robots.find("r1");
  EXPECT_FALSE(r.has_correction);
  EXPECT_EQ(r.map_from_odom().x, 0.0);
  EXPECT_EQ(r.map_from_odom().theta, 0.0);
}

TEST(RobotRegistry, PointsStayRawAndTheBoxFollowsTheCorrection) {
  RobotRegistry robots;
  robots.ingest(observation("r1", {1.0f, 0.0f, 2.0f, 0.0f}));
  PoseCorrectionData c;
  c.robot_id = "r1";
  c.version = 3;
  c.map_from_odom = {5.0, -1.0, std::numbers::pi / 2.0};
  c.source = CorrectionSource::Loop;
  robots.ingest(PoseCorrectionData(c));
  const RobotView& r = *robots.find("r1");
  ASSERT_TRUE(r.has_correction);
  EXPECT_EQ(r.correction.version, 3u);
  EXPECT_EQ(r.points.data()[0], 1.0f);  // raw
  // (1, 0) and (2, 0) rotated a quarter turn and moved by (5, -1): (5, 0) and (5, 1).
  WorldBox box;
  ASSERT_TRUE(robots.bounds(&box));
  EXPECT_NEAR(box.min_x, 5.0, 1e-9);
  EXPECT_NEAR(box.max_x, 5.0, 1e-9);
  EXPECT_NEAR(box.min_y, 0.0, 1e-9);
  EXPECT_NEAR(box.max_y, 1.0, 1e-9);
  EXPECT_STREQ(correction_source_name(r.correction.source), "loop closure");
}

}  // namespace
}  // namespace slam::viewer
