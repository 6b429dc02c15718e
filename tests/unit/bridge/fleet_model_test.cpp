#include "bridge/core/fleet_model.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <vector>

namespace slam::bridge {
namespace {

std::vector<Vec2> points_of(const RobotView& r) {
  std::vector<Vec2> out;
  r.points.for_each([&out](Vec2 p) { out.push_back(p); });
  return out;
}

TEST(FleetModel, PlacesPointsThroughTheRobotsCorrectionAtArrival) {
  FleetModel fleet(10);
  fleet.ingest(ObservationInput{"r1", {{1.0, 0.0}}});
  fleet.ingest(CorrectionInput{"r1", Pose{2.0, 0.0, std::numbers::pi / 2}});
  fleet.ingest(ObservationInput{"r1", {{1.0, 0.0}}});
  const auto points = points_of(fleet.robots().at("r1"));
  ASSERT_EQ(points.size(), 2u);
  EXPECT_DOUBLE_EQ(points[0].x, 1.0);  // before the correction: as reported
  EXPECT_NEAR(points[1].x, 2.0, 1e-12);
  EXPECT_NEAR(points[1].y, 1.0, 1e-12);
}

TEST(FleetModel, KeepsOnlyTheMostRecentPointsPerRobot) {
  FleetModel fleet(3);
  for (int i = 0; i < 5; ++i) fleet.ingest(ObservationInput{"r1", {{static_cast<double>(i), 0.0}}});
  std::vector<double> xs;
  for (const Vec2& p : points_of(fleet.robots().at("r1"))) xs.push_back(p.x);
  std::sort(xs.begin(), xs.end());
  EXPECT_EQ(xs, (std::vector<double>{2.0, 3.0, 4.0}));
}

TEST(FleetModel, CountsChangesPerKind) {
  FleetModel fleet(10);
  const FleetVersions before = fleet.versions();
  fleet.ingest(RobotStateInput{"r1", Pose{1, 2, 0}, true, true, 5});
  fleet.ingest(RobotPathInput{"r1", PathStatus::Active, "planned", {3, 4}, {{3, 4}}, 0});
  fleet.ingest(HeartbeatInput{"mapper", "vm:1", "vm", 1, "running", 2.0}, 100);
  fleet.ingest(ObservationInput{"r1", {}});  // no points: no news
  EXPECT_EQ(fleet.versions().robots, before.robots + 1);
  EXPECT_EQ(fleet.versions().paths, before.paths + 1);
  EXPECT_EQ(fleet.versions().health, before.health + 1);
  EXPECT_EQ(fleet.versions().points, before.points);
  EXPECT_EQ(fleet.services().size(), 1u);
  EXPECT_TRUE(fleet.robots().at("r1").has_state);
}

}  // namespace
}  // namespace slam::bridge
