// The offline --export/--import commands.
#include "mapper/mapper_offline.hpp"

#include <gtest/gtest.h>

#include "mapper/map_files.hpp"
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

}  // namespace
}  // namespace slam::mapper
