#pragma once
// slam-mapper as a black box: the fixture plays the gateway (RobotObservation) and the operator
// (GridConfig, MapEdit, MapFileRequest) on a DDS domain of its own, rebuilds the map from the
// mapper's GridSnapshot + GridTiles samples, and checks it cell by cell. The store lives in the
// process group's directory, so kill -9 and restart use the same file. Generous timeouts: CI
// machines are loaded. Used by mapper_test.cpp (the map) and mapper_operator_test.cpp (requests).
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

#include "common/core/map_io.hpp"
#include "common/fastdds/fast_topics.hpp"
#include "fastdds_inbox.hpp"
#include "observation_batches.hpp"
#include "process_group.hpp"
#include "received_map.hpp"

namespace slam::mapper_test {

using namespace std::chrono_literals;
using testkit::Inbox;
using testkit::wait_until;

// The mapper's layout for these tests: 0.1 m cells, lower-left corner (-5, -5), 10 m x 10 m.
constexpr double kRes = 0.1;
constexpr double kOrigin = -5.0;

inline Point2 pt(double x, double y) {
  Point2 p;
  p.x(x);
  p.y(y);
  return p;
}

using Map = testkit::ReceivedMap;

inline std::optional<Map> assemble(const std::vector<GridSnapshot>& snapshots,
                                   const std::vector<GridTiles>& patches) {
  if (snapshots.empty()) return std::nullopt;
  return testkit::assemble(snapshots.back(), patches);
}

inline RobotObservation observation(const std::string& robot, uint64_t seq, Point2 pose,
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
inline std::vector<Point2> wall_hits() {
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
    observations_ = testkit::make_test_writer(*participant_, dds::kRobotObservations);
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
  void start_mapper(const std::string& snapshot_period = "600", const std::vector<std::string>& extra = {}) {
    std::vector<std::string> args{testkit::bin_path("slam-mapper"),
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
                                  "debug"};
    args.insert(args.end(), extra.begin(), extra.end());
    group_.start("mapper", args);
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

  // The published map once its version held for a second (the mapper commits every patch tick);
  // nothing if it kept changing for a minute.
  std::optional<Map> stable_map() const {
    std::optional<Map> before;
    const bool stable = wait_until(
        [&] {
          auto now = current();
          const bool same = before && now && now->version == before->version;
          before = now;
          return same;
        },
        60s, 1s);
    if (!stable) return std::nullopt;
    return before;
  }

  // Sends the wall `times` times from (0, 0) and waits until the mapper integrated and published it.
  void send_wall(int times, uint64_t first_seq = 1) {
    for (int i = 0; i < times; ++i)
      ASSERT_TRUE(observations_->write(
          testkit::batch_of(observation("r1", first_seq + static_cast<uint64_t>(i), pt(0, 0), wall_hits()))));
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
  std::unique_ptr<dds::Writer<RobotObservationBatch>> observations_;
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

}  // namespace slam::mapper_test
