// The mapper's operator side: map export/import, edits, bad requests answered with reasons, its
// command line and a corrupt store (fixture: mapper_fixture.hpp).
#include "mapper_fixture.hpp"

namespace slam::mapper_test {
namespace {

TEST_F(MapperTest, ExportsImportsEditsAndAnswersBadRequestsWithReasons) {
  start_mapper();
  send_wall(1);
  ASSERT_EQ(edit(1, EDIT_OBSTRUCT, pt(-3.95, -3.95)).result(), MAP_OK);
  ASSERT_TRUE(wait_until(
      [&] {
        auto m = current();
        return m && (m->at(-3.95, -3.95) & CELL_FLAG_OBSTRUCTED);
      },
      30s));
  const Map m = current().value();

  const std::string yaml = group_.dir() + "/export.yaml";
  const MapReply exported = file_request(2, MAP_EXPORT, yaml);
  ASSERT_EQ(exported.result(), MAP_OK) << exported.message();
  auto image = read_ros_map(yaml);
  ASSERT_TRUE(image) << image.message();
  ASSERT_EQ(image->width, m.info.width());
  ASSERT_EQ(image->height, m.info.height());
  EXPECT_DOUBLE_EQ(image->resolution, m.info.resolution());
  EXPECT_DOUBLE_EQ(image->origin_x, m.info.origin().x());
  size_t occupied = 0;
  for (size_t i = 0; i < m.cells.size(); ++i) {
    const bool blocked =
        (m.cells[i] & CELL_STATE_MASK) == CELL_OCCUPIED || (m.cells[i] & CELL_FLAG_OBSTRUCTED);
    EXPECT_EQ(image->cells[i] == kMapOccupied, blocked) << "cell " << i;
    occupied += blocked ? 1 : 0;
  }
  EXPECT_EQ(occupied, wall_hits().size() + 1);

  std::ofstream(group_.dir() + "/garbage.yaml") << "image: [unclosed\n";
  struct Bad {
    uint64_t id;
    MapFileAction action;
    std::string path;
    MapResult result;
  };
  for (const Bad& b : {Bad{10, MAP_EXPORT, group_.dir() + "/map.txt", MAP_INVALID_REQUEST},
                       Bad{11, MAP_EXPORT, "", MAP_INVALID_REQUEST},
                       Bad{12, MAP_EXPORT, "/nonexistent-dir/map.yaml", MAP_IO_ERROR},
                       Bad{13, MAP_IMPORT, group_.dir() + "/missing.yaml", MAP_IO_ERROR},
                       Bad{14, MAP_IMPORT, group_.dir() + "/garbage.yaml", MAP_BAD_FILE}}) {
    const MapReply r = file_request(b.id, b.action, b.path);
    EXPECT_EQ(r.result(), b.result) << "request " << b.id << ": " << r.message();
    EXPECT_FALSE(r.message().to_string().empty()) << "request " << b.id << " has no reason";
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(edit(20, EDIT_OBSTRUCT, pt(nan, 0)).result(), MAP_INVALID_REQUEST);
  EXPECT_EQ(edit(21, EDIT_RESET_ROBOT, pt(0, 0), "ghost").result(), MAP_UNKNOWN_ROBOT);
  EXPECT_EQ(edit(22, EDIT_RESET_ROBOT, pt(0, 0), "").result(), MAP_INVALID_REQUEST);
  EXPECT_EQ(current().value().cells, m.cells) << "refused requests must leave the map alone";

  // Reset: the robot's observations go, the operator's obstruction stays.
  const MapReply reset = edit(30, EDIT_RESET_ROBOT, pt(0, 0), "r1");
  ASSERT_EQ(reset.result(), MAP_OK) << reset.message();
  ASSERT_TRUE(wait_until(
      [&] {
        auto c = current();
        return c && c->state(2.03, 0.03) == CELL_UNKNOWN;
      },
      60s));
  EXPECT_NE(current().value().at(-3.95, -3.95) & CELL_FLAG_OBSTRUCTED, 0);

  // Import the exported map as the prior: the wall is back without any observation.
  const MapReply imported = file_request(31, MAP_IMPORT, yaml);
  ASSERT_EQ(imported.result(), MAP_OK) << imported.message();
  ASSERT_TRUE(wait_until(
      [&] {
        auto c = current();
        return c && c->state(2.03, 0.03) == CELL_OCCUPIED;
      },
      60s));
}

TEST_F(MapperTest, CommandLineHelpBadFlagsCorruptStoreAndOfflineExport) {
  const std::string bin = testkit::bin_path("slam-mapper");
  group_.start("help", {bin, "--help"});
  EXPECT_EQ(group_.wait_exit("help", 60s), 0);
  EXPECT_NE(group_.log("help").find("--export"), std::string::npos)
      << "--help documents the offline commands";
  group_.start("badflag", {bin, "--no-such-flag"});
  EXPECT_EQ(group_.wait_exit("badflag", 60s), 2);
  group_.start("badrate", {bin, "--patch-rate", "0"});
  EXPECT_EQ(group_.wait_exit("badrate", 60s), 2);
  EXPECT_NE(group_.log("badrate").find("patch_rate"), std::string::npos) << group_.log("badrate");

  const std::string corrupt = group_.dir() + "/corrupt.db";
  std::ofstream(corrupt) << std::string(8192, 'x');
  group_.start("corrupt", {bin, "--domain", std::to_string(domain_.id()), "--store", corrupt});
  EXPECT_EQ(group_.wait_exit("corrupt", 60s), 1);
  EXPECT_NE(group_.log("corrupt").find(corrupt), std::string::npos) << group_.log("corrupt");

  // A store written by a running mapper, exported offline after it stopped.
  start_mapper();
  send_wall(1);
  std::this_thread::sleep_for(500ms);  // a patch tick commits the batch; SIGTERM commits the rest anyway
  group_.stop("mapper", SIGTERM);
  const std::string yaml = group_.dir() + "/offline.yaml";
  group_.start("export",
               {bin, "--store", store(), "--grid-resolution", "0.1", "--grid-origin-x", "-5",
                "--grid-origin-y", "-5", "--grid-width-m", "10", "--grid-height-m", "10", "--export", yaml});
  ASSERT_EQ(group_.wait_exit("export", 60s), 0) << group_.log("export");
  auto image = read_ros_map(yaml);
  ASSERT_TRUE(image) << image.message();
  const auto cx = static_cast<size_t>((2.03 - image->origin_x) / image->resolution);
  const auto cy = static_cast<size_t>((0.03 - image->origin_y) / image->resolution);
  EXPECT_EQ(image->cells[cy * image->width + cx], kMapOccupied);

  group_.start("import", {bin, "--store", group_.dir() + "/fresh.db", "--import", yaml});
  EXPECT_EQ(group_.wait_exit("import", 60s), 0) << group_.log("import");
  group_.start("import_bad",
               {bin, "--store", group_.dir() + "/fresh.db", "--import", group_.dir() + "/nope.yaml"});
  EXPECT_EQ(group_.wait_exit("import_bad", 60s), 1);
}

}  // namespace
}  // namespace slam::mapper_test
