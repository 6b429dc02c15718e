// slam-mapper as a black box: this test plays the gateway (RobotObservation) and the operator
// (GridConfig, MapEdit, MapFileRequest) on a DDS domain of its own, rebuilds the map from the
// mapper's GridSnapshot + GridTiles samples, and checks it cell by cell. The store lives in the
// process group's directory, so kill -9 and restart use the same file. Generous timeouts: CI
// machines are loaded.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "common/core/grid_tiles.hpp"
#include "common/core/map_io.hpp"
#include "common/fastdds/fast_topics.hpp"
#include "fastdds_inbox.hpp"
#include "process_group.hpp"

namespace slam {
namespace {

using namespace std::chrono_literals;
using testkit::Inbox;
using testkit::wait_until;

// The mapper's layout for these tests: 0.1 m cells, lower-left corner (-5, -5), 10 m x 10 m.
constexpr double kRes = 0.1;
constexpr double kOrigin = -5.0;

Point2 pt(double x, double y) {
  Point2 p;
  p.x(x);
  p.y(y);
  return p;
}

// The grid as a receiver sees it: the latest snapshot plus the consecutive patches after it.
struct Map {
  uint32_t layout_id = 0;
  uint64_t version = 0;
  GridInfo info;
  std::vector<uint8_t> cells;

  uint8_t at(double x, double y) const {  // the cell holding map-frame point (x, y); 0xff outside
    const auto cx = static_cast<int64_t>(std::floor((x - info.origin().x()) / info.resolution()));
    const auto cy = static_cast<int64_t>(std::floor((y - info.origin().y()) / info.resolution()));
    if (cx < 0 || cy < 0 || cx >= info.width() || cy >= info.height()) return 0xff;
    return cells[static_cast<size_t>(cy) * info.width() + static_cast<size_t>(cx)];
  }
  uint8_t state(double x, double y) const { return static_cast<uint8_t>(at(x, y) & CELL_STATE_MASK); }
};

std::optional<Map> assemble(const std::vector<GridSnapshot>& snapshots,
                            const std::vector<GridTiles>& patches) {
  if (snapshots.empty()) return std::nullopt;
  const GridSnapshot& s = snapshots.back();
  Map m{s.layout_id(), s.version(), s.info(), s.cells()};
  std::map<uint64_t, const GridTiles*> later;
  for (const GridTiles& p : patches)
    if (p.layout_id() == m.layout_id && p.version() > m.version) later[p.version()] = &p;
  for (const auto& [version, p] : later) {
    if (version != m.version + 1) break;
    const TilePatchView view{p->tile_side(), p->encoding(), p->tiles(), p->data()};
    if (!apply_tiles(view, m.cells, static_cast<int32_t>(m.info.width()),
                     static_cast<int32_t>(m.info.height())))
      break;
    m.version = version;
  }
  return m;
}

RobotObservation observation(const std::string& robot, uint64_t seq, Point2 pose,
                             const std::vector<Point2>& hits) {
  RobotObservation o;
  o.robot_id(robot);
  o.seq(seq);
  o.stamp_ns(static_cast<int64_t>(seq) * 1000000);
  o.protocol(PROTOCOL_V2);
  o.pose().x(pose.x());
  o.pose().y(pose.y());
  o.hits(hits);
  return o;
}

// A wall of hits at x = 2.03 for y in [-1, 1] (cell centres avoid boundary rounding at 0.1 and 0.05 m).
std::vector<Point2> wall_hits() {
  std::vector<Point2> hits;
  for (int i = -10; i <= 10; ++i) hits.push_back(pt(2.03, 0.1 * i + 0.03));
  return hits;
}

class MapperTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto p = dds::Participant::create(domain_.id(), "mapper_test");
    ASSERT_TRUE(p) << p.message();
    participant_ = std::move(*p);
    observations_ = testkit::make_test_writer(*participant_, dds::kRobotObservation);
    configs_ = testkit::make_test_writer(*participant_, dds::kGridConfig);
    edits_ = testkit::make_test_writer(*participant_, dds::kMapEdit);
    files_ = testkit::make_test_writer(*participant_, dds::kMapFileRequest);
    snapshot_reader_ = testkit::make_inbox_reader(*participant_, dds::kGridSnapshot, snapshots_);
    patch_reader_ = testkit::make_inbox_reader(*participant_, dds::kGridTiles, patches_);
    reply_reader_ = testkit::make_inbox_reader(*participant_, dds::kMapReply, replies_);
    heartbeat_reader_ = testkit::make_inbox_reader(*participant_, dds::kHeartbeat, heartbeats_);
  }

  void TearDown() override {
    if (HasFailure()) std::cerr << "--- slam-mapper log ---\n" << group_.log("mapper");
  }

  std::string store() const { return group_.dir() + "/map.db"; }

  // Starts the mapper (snapshots only on change unless asked) and waits until it matches every topic.
  void start_mapper(const std::string& snapshot_period = "600") {
    group_.start("mapper", {testkit::bin_path("slam-mapper"),
                            "--domain",
                            std::to_string(domain_.id()),
                            "--store",
                            store(),
                            "--grid-resolution",
                            "0.1",
                            "--grid-origin-x",
                            "-5",
                            "--grid-origin-y",
                            "-5",
                            "--grid-width-m",
                            "10",
                            "--grid-height-m",
                            "10",
                            "--patch-rate",
                            "10",
                            "--snapshot-period",
                            snapshot_period,
                            "--log-level",
                            "debug"});
    ASSERT_TRUE(wait_until(
        [&] {
          return observations_->matched_readers() > 0 && configs_->matched_readers() > 0 &&
                 edits_->matched_readers() > 0 && files_->matched_readers() > 0 &&
                 snapshot_reader_->matched_writers() > 0 && patch_reader_->matched_writers() > 0 &&
                 reply_reader_->matched_writers() > 0;
        },
        60s))
        << "slam-mapper never matched the test's topics\n"
        << group_.log("mapper");
    // Matching is seen from this side first; let the mapper's writers match our readers too.
    std::this_thread::sleep_for(dds::kMatchSettle);
  }

  // The mapper's latest heartbeat value of `name` (-1 before the first heartbeat).
  int64_t counter(const std::string& name) const {
    int64_t value = -1;
    for (const Heartbeat& h : heartbeats_.items()) {
      if (h.service() != "mapper") continue;
      for (const Counter& c : h.counters())
        if (c.name() == name) value = c.value();
    }
    return value;
  }

  std::optional<Map> current() const { return assemble(snapshots_.items(), patches_.items()); }

  // Sends the wall `times` times from (0, 0) and waits until the mapper integrated and published it.
  void send_wall(int times, uint64_t first_seq = 1) {
    for (int i = 0; i < times; ++i)
      ASSERT_TRUE(observations_->write(
          observation("r1", first_seq + static_cast<uint64_t>(i), pt(0, 0), wall_hits())));
    ASSERT_TRUE(wait_until([&] { return counter("observations") >= times; }, 60s))
        << "observations never integrated";
    ASSERT_TRUE(wait_until(
        [&] {
          auto m = current();
          return m && m->state(2.03, 0.03) == CELL_OCCUPIED;
        },
        60s))
        << "the wall never appeared in the published map";
  }

  MapReply wait_reply(uint64_t id) {
    std::optional<MapReply> found;
    EXPECT_TRUE(wait_until(
        [&] {
          for (const MapReply& r : replies_.items())
            if (r.request_id() == id) found = r;
          return found.has_value();
        },
        60s))
        << "no reply to request " << id;
    return found.value_or(MapReply{});
  }

  MapReply file_request(uint64_t id, MapFileAction action, const std::string& path) {
    MapFileRequest r;
    r.request_id(id);
    r.action(action);
    r.yaml_path(path);
    EXPECT_TRUE(files_->write(r));
    return wait_reply(id);
  }

  MapReply edit(uint64_t id, MapEditKind kind, Point2 point, const std::string& robot = "") {
    MapEdit e;
    e.request_id(id);
    e.kind(kind);
    e.point(point);
    e.robot_id(robot);
    EXPECT_TRUE(edits_->write(e));
    return wait_reply(id);
  }

  testkit::DomainLease domain_;
  testkit::ProcessGroup group_;
  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<dds::Writer<RobotObservation>> observations_;
  std::unique_ptr<dds::Writer<GridConfig>> configs_;
  std::unique_ptr<dds::Writer<MapEdit>> edits_;
  std::unique_ptr<dds::Writer<MapFileRequest>> files_;
  Inbox<GridSnapshot> snapshots_;
  Inbox<GridTiles> patches_;
  Inbox<MapReply> replies_;
  Inbox<Heartbeat> heartbeats_;
  std::unique_ptr<dds::Reader<GridSnapshot>> snapshot_reader_;
  std::unique_ptr<dds::Reader<GridTiles>> patch_reader_;
  std::unique_ptr<dds::Reader<MapReply>> reply_reader_;
  std::unique_ptr<dds::Reader<Heartbeat>> heartbeat_reader_;
};

TEST_F(MapperTest, ObservationsBecomePatchesWithFreeRaysAndOccupiedHits) {
  start_mapper();
  ASSERT_TRUE(wait_until([&] { return snapshots_.size() >= 1; }, 60s)) << "no start-up snapshot";
  const GridSnapshot first = snapshots_.items().back();
  EXPECT_EQ(first.info().width(), 100u);
  EXPECT_EQ(first.info().height(), 100u);
  EXPECT_DOUBLE_EQ(first.info().resolution(), kRes);
  EXPECT_DOUBLE_EQ(first.info().origin().x(), kOrigin);
  EXPECT_EQ(std::count(first.cells().begin(), first.cells().end(), CELL_UNKNOWN),
            static_cast<std::ptrdiff_t>(first.cells().size()));

  send_wall(1);
  const Map m = current().value();
  EXPECT_GT(m.version, first.version()) << "patches continue the snapshot's version";
  for (const Point2& h : wall_hits()) {
    EXPECT_EQ(m.state(h.x(), h.y()), CELL_OCCUPIED) << "hit at (" << h.x() << ", " << h.y() << ")";
    EXPECT_EQ(m.state(0.5 * h.x(), 0.5 * h.y()), CELL_FREE)
        << "middle of the ray to (" << h.x() << ", " << h.y() << ")";
  }
  EXPECT_EQ(m.state(3.03, 0.03), CELL_UNKNOWN) << "nothing is known behind the wall";
  EXPECT_NE(m.at(1.93, 0.03) & CELL_FLAG_INFLATED, 0) << "free cells next to the wall are inflated";
  EXPECT_TRUE(wait_until([&] { return counter("patches") >= 1 && counter("points") >= 21; }, 30s));

  // Bad input: rejected, counted, and the map stays as it was.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ASSERT_TRUE(observations_->write(observation("r1", 10, pt(0, 0), {pt(nan, 1)})));
  ASSERT_TRUE(observations_->write(observation("r1", 11, pt(0, 0), {pt(1e9, 1)})));
  ASSERT_TRUE(observations_->write(observation("", 1, pt(0, 0), {pt(1, 1)})));
  ASSERT_TRUE(wait_until([&] { return counter("rejected") >= 3; }, 30s)) << "bad observations not counted";
  std::this_thread::sleep_for(500ms);
  EXPECT_EQ(current().value().cells, m.cells);
  EXPECT_TRUE(group_.running("mapper"));
}

TEST_F(MapperTest, ALateJoiningReaderGetsTheCurrentSnapshotAtOnce) {
  start_mapper();  // periodic snapshots every 600 s: only transient-local history can deliver one
  send_wall(1);
  const Map m = current().value();

  auto p = dds::Participant::create(domain_.id(), "mapper_test_late");
  ASSERT_TRUE(p) << p.message();
  Inbox<GridSnapshot> late;
  auto late_reader = testkit::make_inbox_reader(**p, dds::kGridSnapshot, late);
  ASSERT_TRUE(wait_until(
      [&] {
        for (const GridSnapshot& s : late.items())
          if (s.version() >= m.version) return true;
        return false;
      },
      30s))
      << "the late joiner never got a snapshot with the data";
  const GridSnapshot s = late.items().back();
  EXPECT_EQ(s.cells(), m.cells);
  EXPECT_EQ(s.info().width(), m.info.width());
}

TEST_F(MapperTest, KillNineAndRestartRestoresTheSameMapFromTheStore) {
  start_mapper();
  ASSERT_EQ(edit(1, EDIT_OBSTRUCT, pt(-3.95, -3.95)).result(), MAP_OK);
  // A robot driving along x, seeing the wall at x = 2.03, a wall at y = 3.03 and open space downwards.
  constexpr int kSent = 60;
  for (int i = 0; i < kSent; ++i) {
    const double x = -3.0 + 0.05 * i;
    std::vector<Point2> hits = wall_hits();
    for (int k = -20; k <= 20; ++k) hits.push_back(pt(0.1 * k + 0.03, 3.03));
    RobotObservation o = observation("r2", static_cast<uint64_t>(i + 1), pt(x, 0), hits);
    o.misses({pt(x, -4.0), pt(x + 1.0, -4.0)});
    ASSERT_TRUE(observations_->write(o));
  }
  ASSERT_TRUE(wait_until([&] { return counter("observations") == kSent; }, 60s))
      << "not all observations integrated";
  // Flushed: the mapper commits every patch tick. Wait until the published map stops changing.
  std::optional<Map> before;
  ASSERT_TRUE(wait_until(
      [&] {
        auto now = current();
        const bool stable = before && now && now->version == before->version;
        before = now;
        return stable;
      },
      60s, 1s));
  ASSERT_EQ(before->state(2.03, 0.03), CELL_OCCUPIED);
  ASSERT_EQ(before->state(0.03, 3.03), CELL_OCCUPIED);
  ASSERT_NE(before->at(-3.95, -3.95) & CELL_FLAG_OBSTRUCTED, 0);

  group_.stop("mapper", SIGKILL);
  const size_t seen = snapshots_.size();
  start_mapper();
  ASSERT_TRUE(wait_until([&] { return snapshots_.size() > seen; }, 60s)) << "no snapshot after the restart";
  const GridSnapshot after = snapshots_.items().back();
  EXPECT_EQ(after.info().width(), before->info.width());
  EXPECT_EQ(after.info().height(), before->info.height());
  EXPECT_DOUBLE_EQ(after.info().resolution(), before->info.resolution());
  EXPECT_DOUBLE_EQ(after.info().origin().x(), before->info.origin().x());
  EXPECT_DOUBLE_EQ(after.info().origin().y(), before->info.origin().y());
  EXPECT_TRUE(after.cells() == before->cells)
      << "the restarted mapper's map differs from the one before kill -9";
  EXPECT_TRUE(wait_until([&] { return counter("store_observations") == kSent; }, 30s));

  // Killed in the middle of a stream: at most the last patch period is lost, the store stays usable.
  for (int i = 0; i < 200; ++i)
    ASSERT_TRUE(observations_->write(observation("r3", static_cast<uint64_t>(i + 1), pt(0, 0), wall_hits())));
  std::this_thread::sleep_for(300ms);
  group_.stop("mapper", SIGKILL);
  const size_t seen2 = snapshots_.size();
  start_mapper();
  ASSERT_TRUE(wait_until([&] { return snapshots_.size() > seen2; }, 60s))
      << "no snapshot after the second restart";
  EXPECT_EQ(current().value().state(2.03, 0.03), CELL_OCCUPIED);
  ASSERT_TRUE(wait_until([&] { return counter("store_observations") >= kSent; }, 30s));
  EXPECT_LE(counter("store_observations"), kSent + 200);
}

TEST_F(MapperTest, GridConfigWithANewResolutionRebuildsWithTheSameWalls) {
  start_mapper();
  send_wall(2);
  const size_t seen = snapshots_.size();

  GridConfig bad;
  bad.request_id(7);
  bad.resolution(-1.0);
  bad.origin(pt(-5, -5));
  ASSERT_TRUE(configs_->write(bad));
  const MapReply refused = wait_reply(7);
  EXPECT_EQ(refused.result(), MAP_INVALID_REQUEST);
  EXPECT_NE(refused.message().to_string().find("resolution"), std::string::npos) << refused.message();
  EXPECT_EQ(snapshots_.size(), seen) << "an invalid config must leave the map alone";

  GridConfig good;
  good.request_id(8);
  good.resolution(0.05);
  good.origin(pt(-5, -5));
  good.width_m(10);
  good.height_m(10);
  good.inflation_radius(0.2);
  ASSERT_TRUE(configs_->write(good));
  const MapReply done = wait_reply(8);
  ASSERT_EQ(done.result(), MAP_OK) << done.message();
  ASSERT_TRUE(wait_until(
      [&] {
        auto m = current();
        return m && m->info.resolution() == 0.05;
      },
      60s));
  const Map m = current().value();
  EXPECT_EQ(m.info.width(), 200u);
  for (const Point2& h : wall_hits()) {
    EXPECT_EQ(m.state(h.x(), h.y()), CELL_OCCUPIED) << "hit at (" << h.x() << ", " << h.y() << ")";
    EXPECT_EQ(m.state(0.5 * h.x(), 0.5 * h.y()), CELL_FREE);
  }
  EXPECT_TRUE(wait_until([&] { return counter("rebuilds") >= 1; }, 30s));

  // The store remembers the layout: a restart keeps 0.05 m although the flags say 0.1 m.
  group_.stop("mapper", SIGTERM);
  const size_t before_restart = snapshots_.size();
  start_mapper();
  ASSERT_TRUE(wait_until([&] { return snapshots_.size() > before_restart; }, 60s));
  EXPECT_DOUBLE_EQ(snapshots_.items().back().info().resolution(), 0.05);
  EXPECT_EQ(snapshots_.items().back().cells(), m.cells);
}

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
}  // namespace slam
