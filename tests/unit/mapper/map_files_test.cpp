// Map files: export/import, how failures are sorted, and the start-up layout.
#include "mapper/core/map_files.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "mapper_test_data.hpp"
#include "temp_dir.hpp"

namespace slam::mapper {
namespace {

using test_data::feed;
using test_data::small;

TEST(MapFiles, ExportReadsBackAndFailuresAreSorted) {
  testkit::TempDir dir("mapper");
  auto grid = OccupancyGrid::create(small());
  auto store = open_store(dir.path() / "sub" / "map.db");
  ASSERT_TRUE(store) << store.message();
  feed(*grid, *store);

  const std::string yaml = (dir.path() / "map.yaml").string();
  FileOutcome out = export_map_file(*grid, yaml);
  ASSERT_TRUE(out.ok()) << out.message;
  FileOutcome in = read_map_file(yaml);
  ASSERT_TRUE(in.ok()) << in.message;
  EXPECT_EQ(in.image->cells, grid->to_map_image().cells);

  EXPECT_EQ(export_map_file(*grid, "").failure, MapError::InvalidRequest);
  EXPECT_EQ(export_map_file(*grid, (dir.path() / "map.pgm").string()).failure, MapError::InvalidRequest);
  EXPECT_EQ(export_map_file(*grid, "/nonexistent-dir/map.yaml").failure, MapError::Io);
  EXPECT_EQ(read_map_file((dir.path() / "missing.yaml").string()).failure, MapError::Io);
  std::ofstream(dir.path() / "bad.yaml") << "image: missing.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n";
  const FileOutcome bad = read_map_file((dir.path() / "bad.yaml").string());
  EXPECT_EQ(bad.failure, MapError::BadFile);
  EXPECT_NE(bad.message.find("missing.pgm"), std::string::npos) << bad.message;
}

TEST(MapFiles, StartupLayoutComesFromTheStoreAndTheRestFromTheFlags) {
  testkit::TempDir dir("mapper");
  auto store = open_store(dir.path() / "map.db");
  ASSERT_TRUE(store);
  GridConfig flags = small();
  auto fresh = startup_config(flags, *store);
  ASSERT_TRUE(fresh);
  EXPECT_TRUE(same_layout(*fresh, flags));

  GridConfig saved = small();
  saved.resolution = 0.05;
  saved.legacy_mode = true;
  saved.max_extent_m = 30.0;
  ASSERT_TRUE(store->save_config(saved));
  flags.max_extent_m = 25.0;
  auto loaded = startup_config(flags, *store);
  ASSERT_TRUE(loaded) << loaded.message();
  EXPECT_DOUBLE_EQ(loaded->resolution, 0.05);
  EXPECT_TRUE(loaded->legacy_mode);
  EXPECT_DOUBLE_EQ(loaded->max_extent_m, 25.0) << "limits come from the flags";
}

}  // namespace
}  // namespace slam::mapper
