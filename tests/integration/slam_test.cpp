// Pose correction end to end against the real services:
//  - slam-mapper fed raw RobotObservation samples of a robot with drifting odometry in a synthetic
//    room: its corrections and its map survive kill -9 (the restarted mapper publishes the same
//    corrections, CORRECTION_RESTORED, and the same grid cell for cell);
//  - with global localisation, a laser robot switched on away from the map's origin (odometry at
//    (0, 0, 0)) is found where it truly is, and is still placed there after a kill -9;
//  - `slamctl pose` sets a robot's correction through the mapper, and refuses unknown robots and
//    poses outside the map.
// Generous timeouts: CI machines are loaded. No timings are asserted.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "common/core/geometry.hpp"
#include "common/core/grid_tiles.hpp"
#include "common/fastdds/fast_topics.hpp"
#include "fastdds_inbox.hpp"
#include "observation_batches.hpp"
#include "process_group.hpp"

namespace slam::testkit {
namespace {

constexpr double kPi = std::numbers::pi;

Point2 point(double x, double y) {
  Point2 p;
  p.x(x);
  p.y(y);
  return p;
}

int64_t wall_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// ---------------------------------------------------------------------------------------------
// A synthetic room (walls as segments, world = map frame) and a robot driving a loop in it whose
// odometry frame drifts away from the world a little more with every message.

struct Segment {
  Vec2 a, b;
};

const std::vector<Segment>& room_walls() {
  static const std::vector<Segment> walls{{{-3.0, -2.0}, {3.0, -2.0}}, {{3.0, -2.0}, {3.0, 2.0}},
                                          {{3.0, 2.0}, {-3.0, 2.0}},   {{-3.0, 2.0}, {-3.0, -2.0}},
                                          {{-0.6, 1.2}, {0.7, 1.2}},   {{2.2, -1.1}, {2.2, 0.1}},
                                          {{-2.2, -1.4}, {-1.2, -1.4}}};
  return walls;
}

// Distance along the ray from `o` in direction `angle` to the nearest wall; infinity when none.
double cast(Vec2 o, double angle) {
  const Vec2 d{std::cos(angle), std::sin(angle)};
  double best = std::numeric_limits<double>::infinity();
  for (const Segment& s : room_walls()) {
    const Vec2 e{s.b.x - s.a.x, s.b.y - s.a.y};
    const double denom = d.x * e.y - d.y * e.x;
    if (std::abs(denom) < 1e-12) continue;
    const Vec2 w{s.a.x - o.x, s.a.y - o.y};
    const double t = (w.x * e.y - w.y * e.x) / denom;  // along the ray
    const double u = (w.x * d.y - w.y * d.x) / denom;  // along the segment
    if (t > 1e-9 && u >= 0.0 && u <= 1.0) best = std::min(best, t);
  }
  return best;
}

constexpr int kLoopMessages = 400;  // one loop of 8 m in steps of 0.02 m
constexpr int kBeams = 16;
constexpr double kMaxRange = 4.0;

// True pose after `k` messages: a loop around the rectangle [-1.5, 1.5] x [-0.5, 0.5].
Pose true_pose(int k) {
  double s = std::fmod(0.02 * k, 8.0);
  if (s < 3.0) return {-1.5 + s, -0.5, 0.0};
  s -= 3.0;
  if (s < 1.0) return {1.5, -0.5 + s, kPi / 2};
  s -= 1.0;
  if (s < 3.0) return {1.5 - s, 0.5, kPi};
  s -= 3.0;
  return {-1.5, 0.5 - s, -kPi / 2};
}

// Where the robot's odometry frame lies in the world after `k` messages (its drift so far).
Pose world_from_odom(int k) {
  return Pose{0.0006 * k, -0.0004 * k, 0.0003 * k};
}

// A range sensor: the drifting robot's sparse one, or a laser.
struct Sensor {
  int beams = kBeams;
  double max_range_m = kMaxRange;
};
constexpr Sensor kLaser{180, 8.0};

// A raw observation at `truth` (world frame): pose and hits in the robot's odometry frame.
RobotObservation observation(const std::string& robot, uint64_t seq, const Pose& truth,
                             const Pose& world_from_odom, const Sensor& sensor) {
  const Pose odom_from_world = world_from_odom.inverse();
  const Pose reported = odom_from_world.compose(truth);
  RobotObservation o;
  o.robot_id(robot);
  o.seq(seq);
  o.stamp_ns(wall_now_ns());
  o.protocol(PROTOCOL_V2);
  o.pose().x(reported.x);
  o.pose().y(reported.y);
  o.pose().theta(reported.theta);
  o.has_heading(true);
  std::vector<Point2> hits;
  for (int b = 0; b < sensor.beams; ++b) {
    const double angle = truth.theta + 2 * kPi * b / sensor.beams;
    const double range = cast(truth.position(), angle);
    if (range > sensor.max_range_m) continue;
    const Vec2 world{truth.x + range * std::cos(angle), truth.y + range * std::sin(angle)};
    const Vec2 odom = odom_from_world.transform(world);
    hits.push_back(point(odom.x, odom.y));
  }
  o.hits(hits);
  return o;
}

// The k-th observation of the robot driving the loop with drifting odometry.
RobotObservation drifting_observation(const std::string& robot, int k) {
  return observation(robot, static_cast<uint64_t>(k) + 1, true_pose(k), world_from_odom(k), {});
}

// ---------------------------------------------------------------------------------------------
// The grid as a receiver sees it: the latest snapshot plus the consecutive patches after it.

std::optional<std::vector<uint8_t>> assemble(const std::vector<GridSnapshot>& snapshots,
                                             const std::vector<GridTiles>& patches) {
  if (snapshots.empty()) return std::nullopt;
  const GridSnapshot& s = snapshots.back();
  std::vector<uint8_t> cells = s.cells();
  uint64_t version = s.version();
  std::map<uint64_t, const GridTiles*> later;
  for (const GridTiles& p : patches)
    if (p.layout_id() == s.layout_id() && p.version() > version) later[p.version()] = &p;
  for (const auto& [v, p] : later) {
    if (v != version + 1) break;
    const TilePatchView view{p->tile_side(), p->encoding(), p->tiles(), p->data()};
    if (!apply_tiles(view, cells, static_cast<int32_t>(s.info().width()),
                     static_cast<int32_t>(s.info().height())))
      break;
    version = v;
  }
  return cells;
}

// slam-mapper alone on its own domain; the test plays the gateway and the operator.
class SlamMapperTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto p = dds::Participant::create(domain_.id(), "slam_test");
    ASSERT_TRUE(p) << p.message();
    participant_ = std::move(*p);
    observations_ = make_test_writer(*participant_, dds::kRobotObservations);
    correction_reader_ = make_inbox_reader(*participant_, dds::kPoseCorrection, corrections_);
    snapshot_reader_ = make_inbox_reader(*participant_, dds::kGridSnapshot, snapshots_);
    patch_reader_ = make_inbox_reader(*participant_, dds::kGridTiles, patches_);
  }
  void TearDown() override {
    if (HasFailure()) std::cerr << "--- slam-mapper log ---\n" << group_.log("mapper");
  }

  void start_mapper(const std::vector<std::string>& extra = {}) {
    std::vector<std::string> argv{bin_path("slam-mapper"),
                                  "--domain",
                                  std::to_string(domain_.id()),
                                  "--store",
                                  group_.dir() + "/map.db",
                                  "--grid-resolution",
                                  "0.05",
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
                                  "600",
                                  "--slam",
                                  "on"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    group_.start("mapper", argv);
    ASSERT_TRUE(wait_until(
        [&] {
          return observations_->matched_readers() > 0 && correction_reader_->matched_writers() > 0 &&
                 snapshot_reader_->matched_writers() > 0 && patch_reader_->matched_writers() > 0;
        },
        60s))
        << "slam-mapper never matched the test's topics";
    std::this_thread::sleep_for(dds::kMatchSettle);
  }

  // Publishes messages [first, last) of the drifting robot at 50 Hz (stamps are real time: the
  // mapper closes a silent robot's keyframe by its own clock).
  void drive(const std::string& robot, int first, int last) {
    for (int k = first; k < last; ++k) {
      ASSERT_TRUE(observations_->write(batch_of(drifting_observation(robot, k))));
      std::this_thread::sleep_for(20ms);
    }
  }

  // A laser robot switched on at the loop's message `start`, its odometry at (0, 0, 0) there (its
  // frame is its start pose in the world), drives `messages` steps of the loop at 50 Hz.
  void drive_switched_on(const std::string& robot, int start, int messages) {
    const Pose world_from_odom = true_pose(start);
    for (int j = 0; j < messages; ++j) {
      ASSERT_TRUE(observations_->write(batch_of(
          observation(robot, static_cast<uint64_t>(j) + 1, true_pose(start + j), world_from_odom, kLaser))));
      std::this_thread::sleep_for(20ms);
    }
  }

  // Waits until no PoseCorrection arrived for `quiet` (every keyframe finalised, optimisations landed).
  bool wait_corrections_settle(std::chrono::milliseconds quiet, std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    size_t seen = corrections_.size();
    auto since = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(200ms);
      if (corrections_.size() != seen) {
        seen = corrections_.size();
        since = std::chrono::steady_clock::now();
      } else if (seen > 0 && std::chrono::steady_clock::now() - since >= quiet) {
        return true;
      }
    }
    return false;
  }

  std::optional<PoseCorrection> last_correction(const std::string& robot) const {
    return corrections_.last([&](const PoseCorrection& c) { return c.robot_id() == robot; });
  }

  DomainLease domain_;
  ProcessGroup group_;
  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<dds::Writer<RobotObservationBatch>> observations_;
  Inbox<PoseCorrection> corrections_;
  Inbox<GridSnapshot> snapshots_;
  Inbox<GridTiles> patches_;
  std::unique_ptr<dds::Reader<PoseCorrection>> correction_reader_;
  std::unique_ptr<dds::Reader<GridSnapshot>> snapshot_reader_;
  std::unique_ptr<dds::Reader<GridTiles>> patch_reader_;
};

TEST_F(SlamMapperTest, KillNineKeepsTheCorrectionsAndTheMap) {
  ASSERT_NO_FATAL_FAILURE(start_mapper());
  ASSERT_NO_FATAL_FAILURE(drive("r1", 0, kLoopMessages + 100));
  ASSERT_TRUE(wait_corrections_settle(6s, 60s)) << "the corrections never settled";
  std::this_thread::sleep_for(1500ms);  // the store commits every patch period; the last patch goes out

  const auto before = last_correction("r1");
  ASSERT_TRUE(before);
  const Pose2& c = before->map_from_odom();
  std::printf(
      "slam_test: correction before kill -9: (%.4f, %.4f, %.4f) version %llu keyframes %u source %d\n", c.x(),
      c.y(), c.theta(), static_cast<unsigned long long>(before->version()), before->keyframes(),
      static_cast<int>(before->source()));
  EXPECT_GT(before->keyframes(), 10u);
  EXPECT_GT(std::hypot(c.x(), c.y()), 0.05) << "test setup: the correction is trivial";
  const auto map_before = assemble(snapshots_.items(), patches_.items());
  ASSERT_TRUE(map_before) << "no map before the kill";

  group_.stop("mapper", SIGKILL);
  const size_t snapshots_before = snapshots_.size();
  corrections_.clear();
  ASSERT_NO_FATAL_FAILURE(start_mapper());

  const auto restored = corrections_.wait_for(
      [](const PoseCorrection& r) { return r.robot_id() == "r1" && r.source() == CORRECTION_RESTORED; }, 60s);
  ASSERT_TRUE(restored) << "no restored correction after the restart";
  EXPECT_NEAR(restored->map_from_odom().x(), c.x(), 1e-9);
  EXPECT_NEAR(restored->map_from_odom().y(), c.y(), 1e-9);
  EXPECT_NEAR(restored->map_from_odom().theta(), c.theta(), 1e-9);
  EXPECT_EQ(restored->segment(), before->segment());

  ASSERT_TRUE(wait_until([&] { return snapshots_.size() > snapshots_before; }, 60s))
      << "no snapshot after restart";
  const GridSnapshot after = snapshots_.items()[snapshots_before];
  ASSERT_EQ(after.cells().size(), map_before->size());
  size_t differing = 0;
  for (size_t i = 0; i < map_before->size(); ++i) differing += after.cells()[i] != (*map_before)[i];
  EXPECT_EQ(differing, 0u) << "the restarted mapper's map differs from the one before kill -9";
}

TEST_F(SlamMapperTest, ARobotSwitchedOnAwayFromTheOriginIsPlacedAndKillNineKeepsItPlaced) {
  // Global localisation: r1 maps the room from the origin; r2 is switched on elsewhere, facing the
  // other way, with its odometry at (0, 0, 0). It must be found where it truly is, and stay placed
  // there across a kill -9.
  ASSERT_NO_FATAL_FAILURE(start_mapper({"--slam-global-localisation", "on"}));
  ASSERT_NO_FATAL_FAILURE(drive("r1", 0, kLoopMessages + 50));
  constexpr int kSwitchedOnAt = 250;  // (0.5, 0.5), heading pi
  const Pose truth = true_pose(kSwitchedOnAt);
  ASSERT_NO_FATAL_FAILURE(drive_switched_on("r2", kSwitchedOnAt, 300));
  const auto placed = corrections_.wait_for(
      [](const PoseCorrection& c) { return c.robot_id() == "r2" && c.placement() == PLACEMENT_PLACED; }, 60s);
  ASSERT_TRUE(placed) << "r2 was never placed";
  ASSERT_TRUE(wait_corrections_settle(6s, 60s)) << "the corrections never settled";
  std::this_thread::sleep_for(1500ms);  // the store commits every patch period
  const auto before = last_correction("r2");
  ASSERT_TRUE(before);
  const Pose2& c = before->map_from_odom();
  std::printf("slam_test: r2 placed at (%.3f, %.3f, %.3f), truly at (%.3f, %.3f, %.3f), score %.2f\n", c.x(),
              c.y(), c.theta(), truth.x, truth.y, truth.theta, before->localisation_score());
  EXPECT_EQ(before->placement(), PLACEMENT_PLACED);
  EXPECT_NEAR(c.x(), truth.x, 0.15);
  EXPECT_NEAR(c.y(), truth.y, 0.15);
  EXPECT_NEAR(std::remainder(c.theta() - truth.theta, 2 * kPi), 0.0, 0.1);

  group_.stop("mapper", SIGKILL);
  corrections_.clear();
  ASSERT_NO_FATAL_FAILURE(start_mapper({"--slam-global-localisation", "on"}));
  const auto restored = corrections_.wait_for(
      [](const PoseCorrection& r) { return r.robot_id() == "r2" && r.source() == CORRECTION_RESTORED; }, 60s);
  ASSERT_TRUE(restored) << "no restored correction for r2 after the restart";
  EXPECT_EQ(restored->placement(), PLACEMENT_PLACED) << "the restart forgot where r2 was placed";
  EXPECT_NEAR(restored->map_from_odom().x(), c.x(), 1e-9);
  EXPECT_NEAR(restored->map_from_odom().y(), c.y(), 1e-9);
  EXPECT_NEAR(restored->map_from_odom().theta(), c.theta(), 1e-9);
}

// ---------------------------------------------------------------------------------------------
// slamctl pose end to end.

struct CtlRun {
  int code = -1;
  std::string output;
  size_t lines() const { return static_cast<size_t>(std::count(output.begin(), output.end(), '\n')); }
};

TEST_F(SlamMapperTest, SlamctlPoseSetsTheCorrectionAndPlacementAnswersReachTheMapper) {
  ASSERT_NO_FATAL_FAILURE(start_mapper());
  ASSERT_NO_FATAL_FAILURE(drive("r1", 0, 60));
  // Every keyframe finalised: from here on only the operator changes the correction.
  ASSERT_TRUE(wait_corrections_settle(6s, 60s)) << "the corrections never settled";
  const Pose last_odom = world_from_odom(59).inverse().compose(true_pose(59));

  int runs = 0;
  const auto ctl = [&](std::vector<std::string> args) {
    const std::string name = "slamctl" + std::to_string(++runs);
    std::vector<std::string> argv{bin_path("slamctl"), "--domain", std::to_string(domain_.id()), "--timeout",
                                  "10"};
    argv.insert(argv.end(), args.begin(), args.end());
    group_.start(name, argv);
    CtlRun r;
    r.code = group_.wait_exit(name, 60s);
    r.output = group_.log(name);
    return r;
  };

  const CtlRun ok = ctl({"pose", "r1", "1.25", "-0.75", "30"});
  EXPECT_EQ(ok.code, 0) << ok.output;
  EXPECT_FALSE(ok.output.empty()) << "the reply was not printed";
  std::printf("slam_test: slamctl pose printed: %s", ok.output.c_str());
  const auto set = corrections_.wait_for(
      [](const PoseCorrection& c) { return c.robot_id() == "r1" && c.source() == CORRECTION_OPERATOR; }, 30s);
  ASSERT_TRUE(set) << "no operator correction published";
  const Pose correction{set->map_from_odom().x(), set->map_from_odom().y(), set->map_from_odom().theta()};
  const Pose placed = correction.compose(last_odom);
  EXPECT_NEAR(placed.x, 1.25, 1e-6);
  EXPECT_NEAR(placed.y, -0.75, 1e-6);
  EXPECT_NEAR(std::remainder(placed.theta - 30.0 * kPi / 180.0, 2 * kPi), 0.0, 1e-6);

  const size_t corrections_seen = corrections_.size();
  const CtlRun unknown = ctl({"pose", "nobody", "1", "1", "0"});
  EXPECT_EQ(unknown.code, 1) << unknown.output;
  EXPECT_EQ(unknown.lines(), 1u) << unknown.output;
  EXPECT_NE(unknown.output.find("unknown robot"), std::string::npos) << unknown.output;

  const CtlRun outside = ctl({"pose", "r1", "40", "1", "0"});
  EXPECT_EQ(outside.code, 1) << outside.output;
  EXPECT_EQ(outside.lines(), 1u) << outside.output;
  EXPECT_NE(outside.output.find("outside the map"), std::string::npos) << outside.output;
  EXPECT_EQ(corrections_.size(), corrections_seen) << "a refused pose changed a correction";

  // An operator's answers to a placement: r1 is placed (by the operator), so there is nothing to
  // accept; rejecting it has it searched for again, as a lost robot.
  const CtlRun nothing = ctl({"placement", "accept", "r1"});
  EXPECT_EQ(nothing.code, 1) << nothing.output;
  EXPECT_NE(nothing.output.find("nothing to accept"), std::string::npos) << nothing.output;
  const CtlRun stranger = ctl({"placement", "reject", "nobody"});
  EXPECT_EQ(stranger.code, 1) << stranger.output;
  EXPECT_NE(stranger.output.find("unknown robot"), std::string::npos) << stranger.output;
  EXPECT_EQ(corrections_.size(), corrections_seen) << "a refused answer changed a correction";
  const CtlRun rejected = ctl({"placement", "reject", "r1"});
  EXPECT_EQ(rejected.code, 0) << rejected.output;
  EXPECT_TRUE(corrections_.wait_for(
      [](const PoseCorrection& c) { return c.robot_id() == "r1" && c.placement() == PLACEMENT_LOST; }, 30s))
      << "the rejected robot was not published as searched for";
}

}  // namespace
}  // namespace slam::testkit
