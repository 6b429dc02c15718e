// The mapper's map as a receiver sees it: patches from observations, late joiners, kill -9 and
// restart (also of a compacted store, with slamctl store stats), resolution changes (fixture:
// mapper_fixture.hpp).
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "mapper_fixture.hpp"

namespace slam::mapper_test {
namespace {

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
  ASSERT_TRUE(observations_->write(testkit::batch_of(observation("r1", 10, pt(0, 0), {pt(nan, 1)}))));
  ASSERT_TRUE(observations_->write(testkit::batch_of(observation("r1", 11, pt(0, 0), {pt(1e9, 1)}))));
  ASSERT_TRUE(observations_->write(testkit::batch_of(observation("", 1, pt(0, 0), {pt(1, 1)}))));
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
    ASSERT_TRUE(observations_->write(testkit::batch_of(o)));
  }
  ASSERT_TRUE(wait_until([&] { return counter("observations") == kSent; }, 60s))
      << "not all observations integrated";
  const std::optional<Map> before = stable_map();
  ASSERT_TRUE(before) << "the published map kept changing";
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
    ASSERT_TRUE(observations_->write(
        testkit::batch_of(observation("r3", static_cast<uint64_t>(i + 1), pt(0, 0), wall_hits()))));
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

TEST_F(MapperTest, ACompactedStoreRestartsToTheSameMapAndSlamctlShowsWhatItKeeps) {
  // Stamps are 1 ms per message: a retention of 1e-9 days (86 us) and no minimum age compact all but
  // the newest rows, every 0.2 s of the stream.
  start_mapper("600", {"--store-retention-days", "1e-9", "--store-min-age-s", "0",
                       "--store-compact-interval-s", "0.2", "--slam", "off"});
  constexpr int kSent = 400;
  for (int i = 0; i < kSent; ++i) {
    const double x = -3.0 + 0.01 * i;
    std::vector<Point2> hits = wall_hits();
    for (int k = -20; k <= 20; ++k) hits.push_back(pt(0.1 * k + 0.03, 3.03));
    RobotObservation o = observation("r2", static_cast<uint64_t>(i + 1), pt(x, 0), hits);
    o.misses({pt(x, -4.0), pt(x + 1.0, -4.0)});
    ASSERT_TRUE(observations_->write(testkit::batch_of(o)));
    std::this_thread::sleep_for(2ms);
  }
  ASSERT_TRUE(wait_until([&] { return counter("observations") == kSent; }, 60s));
  ASSERT_TRUE(wait_until([&] { return counter("compactions") >= 1; }, 30s)) << "never compacted";
  const std::optional<Map> before = stable_map();
  ASSERT_TRUE(before) << "the published map kept changing";
  ASSERT_EQ(before->state(2.03, 0.03), CELL_OCCUPIED);
  EXPECT_LT(counter("store_observations"), kSent);
  EXPECT_EQ(counter("store_observations") + counter("compacted_observations"), kSent);

  group_.stop("mapper", SIGKILL);
  const size_t seen = snapshots_.size();
  start_mapper();
  ASSERT_TRUE(wait_until([&] { return snapshots_.size() > seen; }, 60s)) << "no snapshot after the restart";
  EXPECT_TRUE(snapshots_.items().back().cells() == before->cells)
      << "the restarted mapper's map differs from the compacted one before kill -9";

  const std::string command = testkit::bin_path("slamctl") + " store stats --store " + store();
  FILE* out = popen(command.c_str(), "r");
  ASSERT_NE(out, nullptr);
  std::string text;
  char buf[256];
  while (std::fgets(buf, sizeof buf, out)) text += buf;
  EXPECT_EQ(pclose(out), 0) << text;
  EXPECT_NE(text.find("compacted tiles"), std::string::npos) << text;
  EXPECT_EQ(text.find("compacted tiles      0 "), std::string::npos) << text;
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

}  // namespace
}  // namespace slam::mapper_test
