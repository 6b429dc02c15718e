// World specs: built-in names, Java text files and ROS map_server maps (written with the shared
// map writer, read back through load_world).
#include "simulator/core/world_loader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "temp_dir.hpp"

namespace slam::sim {
namespace {

using ::testing::HasSubstr;

TEST(WorldLoader, BuiltinNameAndJavaFile) {
  const auto office = load_world("office");
  ASSERT_TRUE(office) << office.message();
  EXPECT_EQ(office->name(), "office");
  const auto ludo = load_world(std::string(SIM_TEST_WORLDS) + "/ssnar-java/ludo.txt");
  ASSERT_TRUE(ludo) << ludo.message();
  EXPECT_EQ(ludo->name(), "ludo");
  EXPECT_EQ(ludo->walls().size(), 4u + 16u);
}

TEST(WorldLoader, RosMapBecomesWalls) {
  // 20 x 10 free map at 0.1 m with a 2-cell-thick occupied wall at columns 8..9, rows 0..5.
  MapImage map;
  map.width = 20;
  map.height = 10;
  map.resolution = 0.1;
  map.origin_x = -1.0;
  map.origin_y = 0.5;
  map.cells.assign(200, kMapFree);
  for (uint32_t y = 0; y <= 5; ++y)
    for (uint32_t x = 8; x <= 9; ++x) map.cells[y * 20 + x] = kMapOccupied;
  map.cells[199] = kMapUnknown;
  const testkit::TempDir dir("world-loader");
  ASSERT_TRUE(write_ros_map(dir / "wallmap.yaml", map));

  const auto world = load_world((dir / "wallmap.yaml").string());
  ASSERT_TRUE(world) << world.message();
  EXPECT_EQ(world->name(), "wallmap");
  EXPECT_EQ(world->walls().size(), 4u + 3u);  // two sides and the top of the wall
  EXPECT_NEAR(world->bounds().min.x, -1.0, 1e-9);
  EXPECT_NEAR(world->bounds().max.y, 1.5, 1e-9);
  // The wall's left face is at x = -1.0 + 0.8 = -0.2.
  EXPECT_NEAR(world->cast({-0.9, 0.7}, {1, 0}, 5.0), 0.7, 1e-9);
  EXPECT_NEAR(world->cast({-0.9, 1.3}, {1, 0}, 5.0), 1.9, 1e-9);  // above it: the far border
}

TEST(WorldLoader, RotatedMapIsRefused) {
  MapImage map;
  map.width = 2;
  map.height = 2;
  map.cells.assign(4, kMapFree);
  map.origin_yaw = 0.5;
  EXPECT_THAT(world_from_map(map, "tilted").message(), HasSubstr("origin yaw"));
}

TEST(WorldLoader, ErrorsNameTheSpec) {
  EXPECT_THAT(load_world("").message(), HasSubstr("no world given"));
  EXPECT_THAT(load_world("/nonexistent/w.txt").message(), HasSubstr("/nonexistent/w.txt"));
  EXPECT_THAT(load_world("/nonexistent/m.yaml").message(), HasSubstr("m.yaml"));
}

}  // namespace
}  // namespace slam::sim
