// The offline --export/--import/--export-trajectory commands.
#include "mapper/core/mapper_offline.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "mapper/core/map_files.hpp"
#include "mapper_test_data.hpp"
#include "temp_dir.hpp"

namespace slam::mapper {
namespace {

using test_data::feed;
using test_data::small;

TEST(MapperOffline, ExportsTheStoreAndImportsAPrior) {
  testkit::TempDir dir("mapper");
  MapperOptions o;
  o.store = (dir.path() / "map.db").string();
  o.grid = small();
  {
    auto store = open_store(o.store);
    ASSERT_TRUE(store);
    auto grid = OccupancyGrid::create(o.grid);
    feed(*grid, *store);
  }
  o.export_yaml = (dir.path() / "out.yaml").string();
  auto exported = run_offline(o);
  ASSERT_TRUE(exported) << exported.message();
  EXPECT_NE(exported->find("1 observations"), std::string::npos) << *exported;

  MapperOptions imp;
  imp.store = (dir.path() / "other.db").string();
  imp.import_yaml = o.export_yaml;
  auto imported = run_offline(imp);
  ASSERT_TRUE(imported) << imported.message();
  auto store = open_store(imp.store);
  ASSERT_TRUE(store);
  auto prior = store->load_prior();
  ASSERT_TRUE(prior && prior->has_value());

  MapperOptions missing;
  missing.store = (dir.path() / "nope.db").string();
  missing.export_yaml = o.export_yaml;
  auto refused = run_offline(missing);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.message().find("nope.db"), std::string::npos) << refused.message();
}

TEST(MapperOffline, ExportsARobotsTrajectory) {
  testkit::TempDir dir("mapper");
  MapperOptions o;
  o.store = (dir.path() / "map.db").string();
  {
    auto store = open_store(o.store);
    ASSERT_TRUE(store);
    ASSERT_TRUE(store->append("r1", 1, 100, 0, ObservationView{1.0, 2.0, 0.0, false, {}, {}}, 2'500'000'000));
  }
  o.export_trajectory = "r1";
  o.trajectory_out = (dir.path() / "r1.txt").string();
  o.trajectory_format = "carmen";
  auto exported = run_offline(o);
  ASSERT_TRUE(exported) << exported.message();
  EXPECT_NE(exported->find("wrote 1 poses of robot 'r1'"), std::string::npos) << *exported;
  std::ifstream in(o.trajectory_out);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), "ODOM 1.000000 2.000000 0.000000 0 0 0 2.500000000 slamfleet 2.500000000\n");

  o.export_trajectory = "ghost";
  auto unknown = run_offline(o);
  ASSERT_FALSE(unknown);
  EXPECT_NE(unknown.message().find("'ghost' in " + o.store), std::string::npos) << unknown.message();
}

}  // namespace
}  // namespace slam::mapper
