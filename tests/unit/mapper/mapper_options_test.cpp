// MapperOptions: defaults, flags, and validation naming the bad key.
#include "mapper/core/mapper_options.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace slam::mapper {
namespace {

Status parse(MapperOptions& o, std::vector<std::string> args) {
  CLI::App app{"test"};
  add_mapper_options(app, o);
  std::vector<const char*> argv{"slam-mapper"};
  for (const auto& a : args) argv.push_back(a.c_str());
  try {
    app.parse(static_cast<int>(argv.size()), const_cast<char**>(argv.data()));
  } catch (const CLI::ParseError& e) {
    return Error{e.what()};
  }
  return validate(o);
}

TEST(MapperOptions, DefaultsAreValidAndFlagsBind) {
  MapperOptions o;
  EXPECT_TRUE(validate(o));
  ASSERT_TRUE(parse(
      o, {"--store", "/tmp/x.db", "--grid-resolution", "0.1", "--patch-rate", "5", "--snapshot-period", "2",
          "--grid-legacy-mode", "--rerender-min-shift-cells", "0.5", "--rerender-max-tile-fraction", "0.3"}));
  EXPECT_EQ(o.store, "/tmp/x.db");
  EXPECT_DOUBLE_EQ(o.rerender.min_shift_cells, 0.5);
  EXPECT_DOUBLE_EQ(o.rerender.max_tile_fraction, 0.3);
  EXPECT_DOUBLE_EQ(o.grid.resolution, 0.1);
  EXPECT_DOUBLE_EQ(o.patch_rate_hz, 5.0);
  EXPECT_TRUE(o.grid.legacy_mode);
  EXPECT_FALSE(o.offline());
  MapperOptions store;
  ASSERT_TRUE(parse(store, {"--store-retention-days", "2.5", "--store-max-mb", "300", "--store-min-age-s",
                            "900", "--store-compact-interval-s", "30"}));
  EXPECT_DOUBLE_EQ(store.compaction.retention_days, 2.5);
  EXPECT_DOUBLE_EQ(store.compaction.max_mb, 300.0);
  EXPECT_DOUBLE_EQ(store.compaction.min_age_s, 900.0);
  EXPECT_DOUBLE_EQ(store.compaction.interval_s, 30.0);
}

TEST(MapperOptions, ValidationNamesTheBadKey) {
  const auto error = [](void (*change)(MapperOptions&)) {
    MapperOptions o;
    change(o);
    return validate(o).message();
  };
  EXPECT_NE(error([](MapperOptions& o) { o.patch_rate_hz = 0; }).find("patch_rate"), std::string::npos);
  EXPECT_NE(error([](MapperOptions& o) { o.grid.resolution = -1; }).find("grid.resolution"),
            std::string::npos);
  EXPECT_NE(error([](MapperOptions& o) { o.snapshot_period_s = 1e9; }).find("snapshot_period"),
            std::string::npos);
  EXPECT_NE(error([](MapperOptions& o) { o.store.clear(); }).find("store"), std::string::npos);
  EXPECT_NE(
      error([](MapperOptions& o) { o.rerender.max_tile_fraction = 2; }).find("rerender.max_tile_fraction"),
      std::string::npos);
  EXPECT_NE(error([](MapperOptions& o) { o.compaction.min_age_s = -1; }).find("store.min_age_s"),
            std::string::npos);
  MapperOptions both;
  EXPECT_FALSE(parse(both, {"--export", "a.yaml", "--import", "b.yaml"}))
      << "--export and --import exclude each other";
  MapperOptions no_file;
  const Status needs_file = parse(no_file, {"--export-trajectory", "r1"});
  EXPECT_NE(needs_file.message().find("trajectory_out"), std::string::npos) << needs_file.message();
  MapperOptions bad_format;
  EXPECT_FALSE(parse(bad_format, {"--export-trajectory", "r1", "--trajectory-out", "r1.txt",
                                  "--trajectory-format", "kitti"}));
  EXPECT_NE(error([](MapperOptions& o) { o.trajectory_format = "kitti"; }).find("trajectory_format"),
            std::string::npos);
  MapperOptions localising;
  ASSERT_TRUE(parse(localising, {"--localise-only"}));
  EXPECT_TRUE(localising.localise_only);
  MapperOptions without_slam;
  const Status needs_slam = parse(without_slam, {"--localise-only", "--slam", "off"});
  EXPECT_NE(needs_slam.message().find("localise_only"), std::string::npos) << needs_slam.message();
}

TEST(MapperOptions, TrajectoryExportIsAnOfflineCommand) {
  MapperOptions o;
  ASSERT_TRUE(parse(o, {"--export-trajectory", "sim-1", "--trajectory-out", "/tmp/sim-1.txt",
                        "--trajectory-format", "carmen"}));
  EXPECT_TRUE(o.offline());
  EXPECT_EQ(o.export_trajectory, "sim-1");
  EXPECT_EQ(o.trajectory_out, "/tmp/sim-1.txt");
  EXPECT_EQ(o.trajectory_format, "carmen");
  MapperOptions with_map;
  EXPECT_FALSE(parse(with_map, {"--export-trajectory", "r1", "--trajectory-out", "t", "--export", "a.yaml"}));
}

}  // namespace
}  // namespace slam::mapper
