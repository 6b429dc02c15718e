// Pose correction against the simulator's ground truth: a strongly drifting v1 robot exploring the
// office (mosquitto, gateway, mapper, planner, simulator) stays close to the truth in the gateway's
// map-frame RobotState, and much closer than its raw odometry. Errors are RMSE over many samples
// and means over the last tenth of the run, never a single sample; no timings are asserted.
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
#include "common/fastdds/fast_topics.hpp"
#include "process_group.hpp"

namespace slam::testkit {
namespace {

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

TEST(SlamDriftTest, DriftingRobotStaysCloseToTheTruth) {
  constexpr double kSpeed = 4.0;
  constexpr double kSimSeconds = 90.0;
  DomainLease lease;
  ProcessGroup group;
  const std::string domain = std::to_string(lease.id());
  const int port = group.start_mosquitto();
  const std::string broker = "tcp://127.0.0.1:" + std::to_string(port);
  group.start("gateway", {bin_path("slam-gateway"), "--domain", domain, "--broker", broker});
  group.start("mapper", {bin_path("slam-mapper"), "--domain", domain, "--store", group.dir() + "/map.db"});
  group.start("planner",
              {bin_path("slam-planner"), "--domain", domain, "--goal-store", group.dir() + "/goals.json"});
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
  const auto dump_logs = [&] {
    for (const char* s : {"gateway", "mapper", "planner", "simulator"})
      std::cerr << "--- " << s << " log ---\n" << group.log(s) << "\n";
  };

  auto participant = dds::Participant::create(lease.id(), "slam_drift_test");
  ASSERT_TRUE(participant) << participant.message();
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
  auto goals = dds::make_writer(**participant, dds::kNavGoal);
  ASSERT_TRUE(goals) << goals.message();

  ASSERT_TRUE(wait_until([&] { return seen.states() > 0; }, 60s)) << "the robot never reached the gateway";
  ASSERT_TRUE((*goals)->wait_for_readers(30s)) << "the planner does not read goals";
  NavGoal goal;
  goal.robot_id("*");
  goal.goal_id(1);
  goal.mode(GOAL_EXPLORE);
  ASSERT_TRUE((*goals)->write(goal));

  // Pair samples as they come (the odometry history is short), for the simulated duration.
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(kSimSeconds / kSpeed);
  while (std::chrono::steady_clock::now() < end) {
    std::this_thread::sleep_for(500ms);
    (void)seen.pairs(0.15);
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
  std::printf(
      "slam_drift_test: %zu pairs; corrected RMSE %.3f m (end %.3f m), raw RMSE %.3f m (end %.3f m)\n",
      pairs.size(), corrected_rmse, corrected_end, std::sqrt(raw_sq / static_cast<double>(pairs.size())),
      raw_end);
  EXPECT_GT(raw_end, 0.25) << "test setup: the raw odometry did not drift enough to tell";
  EXPECT_LT(corrected_rmse, 0.15);
  EXPECT_LT(corrected_end, raw_end / 2);
  if (::testing::Test::HasFailure()) dump_logs();
}

}  // namespace
}  // namespace slam::testkit
