// Pose correction against the simulator's ground truth, in the deployment case: the map is known.
// The office's walls are rendered into a ROS map and imported into the mapper as its prior; then a
// strongly drifting v1 robot tours the rooms (mosquitto, gateway, mapper, planner, simulator) and its
// map-frame RobotState from the gateway stays close to the truth, much closer than its raw odometry.
// (Without a prior a lone robot builds its map from its own drifting poses, so nothing ties it to
// the world until it closes a loop.) Errors are RMSE over many samples and means over the last tenth
// of the run, never a single sample; no timings are asserted.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <iostream>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "common/core/geometry.hpp"
#include "common/core/map_io.hpp"
#include "common/fastdds/fast_topics.hpp"
#include "fastdds_inbox.hpp"
#include "process_group.hpp"
#include "simulator/core/builtin_worlds.hpp"

namespace slam::testkit {
namespace {

// The world as a ROS map: cells a wall passes through occupied, the rest of the floor free, filled
// furniture and a margin around the bounds unknown; the origin is the world frame's.
MapImage render_prior(const sim::World& world, double resolution) {
  constexpr double kMargin = 0.5;
  const sim::Bounds& b = world.bounds();
  MapImage map;
  map.resolution = resolution;
  map.origin_x = b.min.x - kMargin;
  map.origin_y = b.min.y - kMargin;
  map.width = static_cast<uint32_t>(std::ceil((b.width() + 2 * kMargin) / resolution));
  map.height = static_cast<uint32_t>(std::ceil((b.height() + 2 * kMargin) / resolution));
  map.cells.assign(size_t{map.width} * map.height, kMapUnknown);
  const auto cell_of = [&](Vec2 p) -> uint8_t* {
    const auto col = static_cast<int64_t>(std::floor((p.x - map.origin_x) / resolution));
    const auto row = static_cast<int64_t>(std::floor((p.y - map.origin_y) / resolution));
    if (col < 0 || row < 0 || col >= map.width || row >= map.height) return nullptr;
    return &map.cells[static_cast<size_t>(row) * map.width + static_cast<size_t>(col)];
  };
  for (uint32_t row = 0; row < map.height; ++row)
    for (uint32_t col = 0; col < map.width; ++col) {
      const Vec2 centre{map.origin_x + (col + 0.5) * resolution, map.origin_y + (row + 0.5) * resolution};
      if (b.contains(centre) && world.is_free(centre, 0.0)) *cell_of(centre) = kMapFree;
    }
  // Walk every wall in quarter-cell steps so no cell it crosses is skipped.
  for (const sim::Segment& w : world.walls()) {
    const double length = std::hypot(w.b.x - w.a.x, w.b.y - w.a.y);
    const int steps = std::max(1, static_cast<int>(std::ceil(length / (resolution / 4))));
    for (int i = 0; i <= steps; ++i) {
      const double t = static_cast<double>(i) / steps;
      if (uint8_t* c = cell_of(Vec2{w.a.x + t * (w.b.x - w.a.x), w.a.y + t * (w.b.y - w.a.y)}))
        *c = kMapOccupied;
    }
  }
  return map;
}

// What the test hears, written by listener threads. Each RobotState is paired with the RobotOdometry
// published beside it (same stamp). Each ground-truth sample is paired with the state whose raw
// odometry pose is nearest to the pose the simulator reported at that instant, moved by the small
// difference between the two, so both sides describe the same moment whatever the delivery lag.
class DriftObserver {
 public:
  void on_state(const RobotState& s) {
    std::lock_guard lock(mutex_);
    states_[s.last_seen_ns()] = Vec2{s.pose().x(), s.pose().y()};
  }
  void on_odometry(const RobotOdometry& o) {
    std::lock_guard lock(mutex_);
    odometry_.push_back({o.stamp_ns(), Vec2{o.odom_pose().x(), o.odom_pose().y()}});
    if (odometry_.size() > 100) odometry_.pop_front();  // about 2.5 s at 10 Hz x speed 4
  }
  void on_truth(const SimGroundTruth& t) {
    if (t.paused() || t.robots().empty()) return;
    const SimRobotTruth& r = t.robots()[0];
    std::lock_guard lock(mutex_);
    truths_.push_back(
        {Vec2{r.true_pose().x(), r.true_pose().y()}, Vec2{r.reported_pose().x(), r.reported_pose().y()}});
  }

  struct Pair {
    double corrected_m;
    double raw_m;
  };
  // Pairs the truth samples received since the last call (one report apart at most: `tolerance`)
  // and returns every pair so far.
  std::vector<Pair> pairs(double tolerance) {
    std::lock_guard lock(mutex_);
    for (const Truth& t : truths_) {
      const Odometry* best = nullptr;
      double best_d = tolerance;
      for (const Odometry& o : odometry_) {
        const double d = std::hypot(o.pose.x - t.reported.x, o.pose.y - t.reported.y);
        if (d <= best_d) best = &o, best_d = d;
      }
      const auto state = best ? states_.find(best->stamp_ns) : states_.end();
      if (state == states_.end()) continue;
      const Vec2 corrected{state->second.x + t.reported.x - best->pose.x,
                           state->second.y + t.reported.y - best->pose.y};
      pairs_.push_back({std::hypot(corrected.x - t.truth.x, corrected.y - t.truth.y),
                        std::hypot(t.reported.x - t.truth.x, t.reported.y - t.truth.y)});
    }
    truths_.clear();
    return pairs_;
  }
  size_t states() const {
    std::lock_guard lock(mutex_);
    return states_.size();
  }

 private:
  struct Odometry {
    int64_t stamp_ns;
    Vec2 pose;
  };
  struct Truth {
    Vec2 truth, reported;
  };
  mutable std::mutex mutex_;
  std::map<int64_t, Vec2> states_;
  std::deque<Odometry> odometry_;
  std::vector<Truth> truths_;
  std::vector<Pair> pairs_;
};

TEST(SlamDriftTest, DriftingRobotOnAKnownMapStaysCloseToTheTruth) {
  constexpr double kSpeed = 4.0;
  constexpr double kSimSeconds = 90.0;
  // Room centres on both sides of the corridor, driven in turn (the tour repeats if time is left).
  const std::vector<Point2> kTour = [] {
    std::vector<Point2> tour;
    for (auto [x, y] : {std::pair{3.0, 3.5},
                        {7.5, 3.0},
                        {12.5, 3.0},
                        {17.5, 4.0},
                        {17.0, 12.0},
                        {11.0, 11.0},
                        {6.0, 12.0},
                        {2.0, 12.0}}) {
      Point2 p;
      p.x(x);
      p.y(y);
      tour.push_back(p);
    }
    return tour;
  }();
  DomainLease lease;
  ProcessGroup group;
  const std::string domain = std::to_string(lease.id());
  const int port = group.start_mosquitto();
  const std::string broker = "tcp://127.0.0.1:" + std::to_string(port);
  // Every state and its odometry at 10 Hz: the observer pairs each truth sample with them.
  group.start("gateway",
              {bin_path("slam-gateway"), "--domain", domain, "--broker", broker, "--state-period-s", "0.1"});
  group.start("mapper", {bin_path("slam-mapper"), "--domain", domain, "--store", group.dir() + "/map.db"});
  group.start("planner",
              {bin_path("slam-planner"), "--domain", domain, "--goal-store", group.dir() + "/goals.json"});
  const auto dump_logs = [&] {
    for (const char* s : {"gateway", "mapper", "planner", "simulator"})
      std::cerr << "--- " << s << " log ---\n" << group.log(s) << "\n";
  };

  auto participant = dds::Participant::create(lease.id(), "slam_drift_test");
  ASSERT_TRUE(participant) << participant.message();

  // The prior: the simulator's own world, imported before any robot reports.
  auto world = sim::builtin_world("office");
  ASSERT_TRUE(world) << world.message();
  const std::string prior_yaml = group.dir() + "/office.yaml";
  const Status written = write_ros_map(prior_yaml, render_prior(*world, 0.05));
  ASSERT_TRUE(written) << written.message();
  auto files = make_test_writer(**participant, dds::kMapFileRequest);
  Inbox<MapReply> replies;
  auto reply_reader = make_inbox_reader(**participant, dds::kMapReply, replies);
  ASSERT_TRUE(files->wait_for_readers(60s)) << "the mapper does not read file requests";
  MapFileRequest import;
  import.request_id(1);
  import.action(MAP_IMPORT);
  import.yaml_path(prior_yaml);
  ASSERT_TRUE(files->write(import));
  const auto imported = replies.wait_for([](const MapReply& r) { return r.request_id() == 1; }, 60s);
  ASSERT_TRUE(imported) << "the mapper never answered the import";
  ASSERT_EQ(imported->result(), MAP_OK) << imported->message();

  group.start("simulator", {bin_path("slam-simulator"),
                            "--domain",
                            domain,
                            "--broker",
                            broker,
                            "--world",
                            "office",
                            "--robots",
                            "1",
                            "--protocol",
                            "v1",
                            "--speed",
                            std::to_string(kSpeed),
                            "--drift",
                            "0.06",
                            "--heading-drift",
                            "0.03",
                            "--seed",
                            "11",
                            "--truth-rate",
                            "20"});
  DriftObserver seen;
  auto states = dds::make_reader(**participant, dds::kRobotState,
                                 [&](const RobotState& s, const auto&) { seen.on_state(s); });
  ASSERT_TRUE(states) << states.message();
  auto odometry = dds::make_reader(**participant, dds::kRobotOdometry,
                                   [&](const RobotOdometry& o, const auto&) { seen.on_odometry(o); });
  ASSERT_TRUE(odometry) << odometry.message();
  auto truth = dds::make_reader(**participant, dds::kSimGroundTruth,
                                [&](const SimGroundTruth& t, const auto&) { seen.on_truth(t); });
  ASSERT_TRUE(truth) << truth.message();
  Inbox<RobotPath> paths;
  auto path_reader = make_inbox_reader(**participant, dds::kRobotPath, paths);
  auto goals = dds::make_writer(**participant, dds::kNavGoal);
  ASSERT_TRUE(goals) << goals.message();

  ASSERT_TRUE(wait_until([&] { return seen.states() > 0; }, 60s)) << "the robot never reached the gateway";
  ASSERT_TRUE((*goals)->wait_for_readers(30s)) << "the planner does not read goals";
  // Exploration would stop at once on a known map: drive the tour with planned goals instead, the
  // next one when the planner reports the current one reached or failed.
  uint64_t goal_id = 0;
  const auto send_next_goal = [&] {
    NavGoal goal;
    goal.robot_id("*");
    goal.goal_id(++goal_id);
    goal.mode(GOAL_PLANNED);
    goal.target(kTour[(goal_id - 1) % kTour.size()]);
    return (*goals)->write(goal);
  };
  ASSERT_TRUE(send_next_goal());

  // Pair samples as they come (the odometry history is short), for the simulated duration.
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(kSimSeconds / kSpeed);
  while (std::chrono::steady_clock::now() < end) {
    std::this_thread::sleep_for(500ms);
    (void)seen.pairs(0.15);
    const bool finished = paths
                              .last([&](const RobotPath& p) {
                                return p.goal_id() == goal_id && (p.status() == GOAL_STATUS_REACHED ||
                                                                  p.status() == GOAL_STATUS_FAILED);
                              })
                              .has_value();
    if (finished) {
      ASSERT_TRUE(send_next_goal());
    }
  }
  const std::vector<DriftObserver::Pair> pairs = seen.pairs(0.15);
  ASSERT_GE(pairs.size(), 100u) << "too few paired samples";

  double corrected_sq = 0.0;
  for (const auto& p : pairs) corrected_sq += p.corrected_m * p.corrected_m;
  const double corrected_rmse = std::sqrt(corrected_sq / static_cast<double>(pairs.size()));
  // Errors at the end: means over the last tenth of the run (one sample is noisy).
  const size_t tail = std::max<size_t>(pairs.size() / 10, 1);
  double raw_end = 0.0, corrected_end = 0.0;
  for (size_t i = pairs.size() - tail; i < pairs.size(); ++i) {
    raw_end += pairs[i].raw_m / static_cast<double>(tail);
    corrected_end += pairs[i].corrected_m / static_cast<double>(tail);
  }
  // The errors over the run, ten points, so a failure shows when the correction went astray.
  for (size_t i = 0; i < pairs.size(); i += std::max<size_t>(pairs.size() / 10, 1))
    std::printf("slam_drift_test: pair %3zu: corrected %.3f m, raw %.3f m\n", i, pairs[i].corrected_m,
                pairs[i].raw_m);
  double raw_sq = 0.0;
  for (const auto& p : pairs) raw_sq += p.raw_m * p.raw_m;
  const double raw_rmse = std::sqrt(raw_sq / static_cast<double>(pairs.size()));
  std::printf(
      "slam_drift_test: %zu pairs; corrected RMSE %.3f m (end %.3f m), raw RMSE %.3f m (end %.3f m)\n",
      pairs.size(), corrected_rmse, corrected_end, raw_rmse, raw_end);
  // Over the whole run, not at its end: the raw error of a random walk may happen to come back
  // near zero by the last samples, which says nothing about the correction.
  EXPECT_GT(raw_rmse, 0.15) << "test setup: the raw odometry did not drift enough to tell";
  EXPECT_LT(corrected_rmse, 0.15);
  EXPECT_LT(corrected_rmse, raw_rmse / 2);
  std::printf("slam_drift_test: %llu tour goals sent\n", static_cast<unsigned long long>(goal_id));
  if (::testing::Test::HasFailure()) dump_logs();
}

}  // namespace
}  // namespace slam::testkit
