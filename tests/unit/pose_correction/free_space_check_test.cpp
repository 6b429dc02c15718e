// crossed_wall_share: a ray counts when it runs through a wall before its last stretch, wherever
// the pose puts it; rays ending on a wall or off the map do not.
#include "pose_correction/free_space_check.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <vector>

#include "synthetic_world.hpp"

namespace slam::correction {
namespace {

// A 10 x 10 m map at 5 cm with one wall across it at x = 5.
testkit::ClassGrid wall_at_five() {
  testkit::SyntheticWorld w;
  w.wall({5.0, 0.0}, {5.0, 10.0});
  return testkit::ClassGrid::rasterise(w, GridGeometry{{0.0, 0.0}, 0.05, 200, 200});
}

TEST(CrossedWallShare, CountsOnlyRaysThatRunThroughAWall) {
  const auto map = wall_at_five();
  const GridView view{map.geometry, map.classes};
  const std::vector<Ray> rays{
      {{1.0, 5.0}, {5.0, 5.0}},  // ends on the wall
      {{1.0, 5.0}, {8.0, 5.0}},  // through it
      {{1.0, 2.0}, {4.0, 3.0}},  // short of it
      {{6.0, 5.0}, {9.0, 5.0}},  // beyond it
  };
  EXPECT_DOUBLE_EQ(crossed_wall_share(view, Pose{}, rays, 0.3), 0.25);
}

TEST(CrossedWallShare, ReadsTheRaysWhereThePosePutsThem) {
  const auto map = wall_at_five();
  const GridView view{map.geometry, map.classes};
  // Seen from (2, 5) looking along +x, a return 2 m ahead stops short of the wall...
  const std::vector<Ray> rays{{{0.0, 0.0}, {2.0, 0.0}}};
  EXPECT_DOUBLE_EQ(crossed_wall_share(view, Pose{2.0, 5.0, 0.0}, rays, 0.3), 0.0);
  // ...and placed at (4, 5), or at (6, 5) turned half round, the same ray runs through it.
  EXPECT_DOUBLE_EQ(crossed_wall_share(view, Pose{4.0, 5.0, 0.0}, rays, 0.3), 1.0);
  EXPECT_DOUBLE_EQ(crossed_wall_share(view, Pose{6.0, 5.0, std::numbers::pi}, rays, 0.3), 1.0);
}

TEST(CrossedWallShare, NothingToReadIsNoCrossing) {
  const auto map = wall_at_five();
  const GridView view{map.geometry, map.classes};
  EXPECT_DOUBLE_EQ(crossed_wall_share(view, Pose{}, {}, 0.3), 0.0);
  const std::vector<Ray> off_map{{{-50.0, -50.0}, {-40.0, -50.0}}};
  EXPECT_DOUBLE_EQ(crossed_wall_share(view, Pose{}, off_map, 0.3), 0.0);
  const std::vector<Ray> shorter_than_margin{{{4.9, 5.0}, {5.1, 5.0}}};
  EXPECT_DOUBLE_EQ(crossed_wall_share(view, Pose{}, shorter_than_margin, 0.3), 0.0);
}

}  // namespace
}  // namespace slam::correction

namespace slam::correction {
namespace {

TEST(ThinEvenly, KeepsEveryStrideThRayAndAtMostTheLimit) {
  std::vector<Ray> rays;
  for (int i = 0; i < 10; ++i) rays.push_back({{0.0, 0.0}, {static_cast<double>(i), 0.0}});
  std::vector<Ray> few = rays;
  thin_evenly(few, 20);
  EXPECT_EQ(few.size(), 10u);  // under the limit: all stay
  thin_evenly(rays, 4);        // stride 3: rays 0, 3, 6, 9
  ASSERT_EQ(rays.size(), 4u);
  for (size_t k = 0; k < rays.size(); ++k) EXPECT_DOUBLE_EQ(rays[k].end.x, 3.0 * static_cast<double>(k));
}

}  // namespace
}  // namespace slam::correction
