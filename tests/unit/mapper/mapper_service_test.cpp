// The mapper service's plain-C++ parts: options (defaults, flags, validation naming the key), map
// files (export/import and how failures are sorted), the start-up layout, the rebuild worker, and
// the offline --export/--import commands.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <thread>

#include "mapper/map_files.hpp"
#include "mapper/mapper_offline.hpp"
#include "mapper/mapper_options.hpp"
#include "mapper/rebuild_worker.hpp"
#include "temp_dir.hpp"

namespace slam::mapper {
namespace {

using namespace std::chrono_literals;

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

GridConfig small() {
  GridConfig c;
  c.resolution = 0.1;
  c.origin_x = -2.0;
  c.origin_y = -2.0;
  c.width_m = 4.0;
  c.height_m = 4.0;
  c.max_extent_m = 20.0;
  return c;
}

// A robot at the origin seeing a wall at x = 1.03.
void feed(OccupancyGrid& grid, ObservationStore& store) {
  std::vector<Vec2> hits;
  for (int i = -5; i <= 5; ++i) hits.push_back({1.03, 0.1 * i + 0.03});
  ObservationView v;
  v.hits = hits;
  ASSERT_TRUE(grid.integrate(v));
  ASSERT_TRUE(store.append("r1", 1, 0, v));
  ASSERT_TRUE(store.flush());
}

TEST(MapperOptions, DefaultsAreValidAndFlagsBind) {
  MapperOptions o;
  EXPECT_TRUE(validate(o));
  ASSERT_TRUE(parse(o, {"--store", "/tmp/x.db", "--grid-resolution", "0.1", "--patch-rate", "5",
                        "--snapshot-period", "2", "--grid-legacy-mode"}));
  EXPECT_EQ(o.store, "/tmp/x.db");
  EXPECT_DOUBLE_EQ(o.grid.resolution, 0.1);
  EXPECT_DOUBLE_EQ(o.patch_rate_hz, 5.0);
  EXPECT_TRUE(o.grid.legacy_mode);
  EXPECT_FALSE(o.offline());
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
  MapperOptions both;
  EXPECT_FALSE(parse(both, {"--export", "a.yaml", "--import", "b.yaml"}))
      << "--export and --import exclude each other";
}

TEST(MapFiles, ExportReadsBackAndFailuresAreSorted) {
  TempDir dir;
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

  EXPECT_EQ(export_map_file(*grid, "").failure, FileFailure::InvalidRequest);
  EXPECT_EQ(export_map_file(*grid, (dir.path() / "map.pgm").string()).failure, FileFailure::InvalidRequest);
  EXPECT_EQ(export_map_file(*grid, "/nonexistent-dir/map.yaml").failure, FileFailure::Io);
  EXPECT_EQ(read_map_file((dir.path() / "missing.yaml").string()).failure, FileFailure::Io);
  std::ofstream(dir.path() / "bad.yaml") << "image: missing.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n";
  const FileOutcome bad = read_map_file((dir.path() / "bad.yaml").string());
  EXPECT_EQ(bad.failure, FileFailure::BadFile);
  EXPECT_NE(bad.message.find("missing.pgm"), std::string::npos) << bad.message;
}

TEST(MapFiles, StartupLayoutComesFromTheStoreAndTheRestFromTheFlags) {
  TempDir dir;
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

TEST(RebuildWorker, RebuildsOffThreadAndHandsTheGridBackOnce) {
  TempDir dir;
  const auto path = dir.path() / "map.db";
  auto store = open_store(path);
  ASSERT_TRUE(store);
  auto live = OccupancyGrid::create(small());
  feed(*live, *store);

  std::atomic<int> done{0};
  RebuildWorker worker([&] { ++done; });
  GridConfig finer = small();
  finer.resolution = 0.05;
  ASSERT_TRUE(worker.start(finer, path));
  EXPECT_TRUE(worker.busy());
  EXPECT_FALSE(worker.start(finer, path)) << "one rebuild at a time";
  auto outcome = worker.wait();
  ASSERT_TRUE(outcome);
  ASSERT_TRUE(outcome->grid) << outcome->grid.message();
  EXPECT_EQ(outcome->stats.observations, 1);
  EXPECT_DOUBLE_EQ(outcome->grid->resolution(), 0.05);
  std::optional<Cell> c;
  c = outcome->grid->cell_at({1.03, 0.03});
  ASSERT_TRUE(c);
  EXPECT_EQ(outcome->grid->cell_class(c->x, c->y) & kCellStateMask, kCellOccupied);
  EXPECT_EQ(done.load(), 1);
  EXPECT_FALSE(worker.busy());
  EXPECT_FALSE(worker.take()) << "handed back once";

  ASSERT_TRUE(worker.start(finer, dir.path() / "no-such-dir" / "map.db"));
  auto failed = worker.wait();
  ASSERT_TRUE(failed);
  EXPECT_FALSE(failed->grid) << "an unreadable store is an error, not an empty map";
}

TEST(MapperOffline, ExportsTheStoreAndImportsAPrior) {
  TempDir dir;
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
