// Exploration end to end: mosquitto, gateway, mapper, planner and three simulated robots in the
// built-in maze; one NavGoal EXPLORE for "*" and nothing else. Within a bounded time the mapper's
// grid must cover most of the maze's reachable free space, and what it claims to know must match
// the hidden world (world_truth.hpp). The simulator runs faster than real time so the maze fits in
// the test's budget; 32 beams per scan (the default 16 also gets there, after more driving and so
// more drift). Per-metre odometry drift is off; heading drift (no flag) is not, so the map slowly
// skews and the agreement threshold leaves room for it. Each judged snapshot is printed
// with the robots' worst odometry error, so a failure says whether the map or the robots drifted.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "common/fastdds/fast_topics.hpp"
#include "process_group.hpp"
#include "simulator/core/builtin_worlds.hpp"
#include "world_truth.hpp"

namespace slam {
namespace {

using namespace std::chrono_literals;
using testkit::wait_until;

constexpr const char* kWorld = "maze";
constexpr int kRobots = 3;
constexpr double kSpeed = 4.0;  // simulated seconds per wall-clock second
constexpr auto kBudget = 150s;  // wall clock, from the goal to the verdict
constexpr double kCoverageWanted = 0.80;
constexpr double kAgreementWanted = 0.95;
constexpr double kWallToleranceM = 0.1;  // two cells of 0.05 m

// What the test hears on DDS, written by listener threads, read by the test thread.
class Observer {
 public:
  void on_snapshot(const GridSnapshot& s) {
    std::lock_guard lock(mutex_);
    snapshot_ = s;
    ++snapshots_;
  }
  void on_state(const RobotState& s) {
    std::lock_guard lock(mutex_);
    starts_.try_emplace(s.robot_id().to_string(), Vec2{s.pose().x(), s.pose().y()});
  }
  void on_path(const RobotPath& p) {
    std::lock_guard lock(mutex_);
    paths_[p.robot_id().to_string()] = p;
  }
  // How far the robots' odometry has wandered from the truth: position (m) and heading (rad).
  void on_truth(const SimGroundTruth& t) {
    std::lock_guard lock(mutex_);
    for (const SimRobotTruth& r : t.robots()) {
      const double dp =
          std::hypot(r.true_pose().x() - r.reported_pose().x(), r.true_pose().y() - r.reported_pose().y());
      const double dh = std::abs(std::remainder(r.true_pose().theta() - r.reported_pose().theta(), 2 * M_PI));
      drift_m_ = std::max(drift_m_, dp);
      drift_rad_ = std::max(drift_rad_, dh);
    }
  }
  std::pair<double, double> drift() const {
    std::lock_guard lock(mutex_);
    return {drift_m_, drift_rad_};
  }
  size_t snapshots() const {
    std::lock_guard lock(mutex_);
    return snapshots_;
  }
  std::optional<GridSnapshot> snapshot() const {
    std::lock_guard lock(mutex_);
    return snapshot_;
  }
  std::vector<Vec2> starts() const {
    std::lock_guard lock(mutex_);
    std::vector<Vec2> out;
    for (const auto& [id, p] : starts_) out.push_back(p);
    return out;
  }
  // Robots whose exploration goal is over: home again (REACHED), or FAILED (home out of reach).
  int finished(uint64_t goal_id) const {
    std::lock_guard lock(mutex_);
    int n = 0;
    for (const auto& [id, p] : paths_) {
      const bool over = p.status() == GOAL_STATUS_REACHED || p.status() == GOAL_STATUS_FAILED;
      n += p.goal_id() == goal_id && over ? 1 : 0;
    }
    return n;
  }

 private:
  mutable std::mutex mutex_;
  std::optional<GridSnapshot> snapshot_;
  size_t snapshots_ = 0;
  std::map<std::string, Vec2> starts_;
  std::map<std::string, RobotPath> paths_;
  double drift_m_ = 0.0;
  double drift_rad_ = 0.0;
};

testkit::MapScore score(const sim::World& world, const GridSnapshot& s, const std::vector<Vec2>& starts) {
  const GridInfo& info = s.info();
  const testkit::TruthLayout layout{info.width(), info.height(), info.resolution(), info.origin().x(),
                                    info.origin().y()};
  const testkit::WorldTruth truth(world, layout, starts);
  return truth.score(layout, s.cells(), kWallToleranceM);
}

TEST(ExploreTest, ThreeRobotsMapTheMaze) {
  testkit::DomainLease lease;
  testkit::ProcessGroup group;
  const std::string domain = std::to_string(lease.id());
  const int port = group.start_mosquitto();
  const std::string broker = "tcp://127.0.0.1:" + std::to_string(port);
  group.start("gateway", {testkit::bin_path("slam-gateway"), "--domain", domain, "--broker", broker});
  group.start("mapper", {testkit::bin_path("slam-mapper"), "--domain", domain, "--store",
                         group.dir() + "/map.db", "--snapshot-period", "1"});
  group.start("planner", {testkit::bin_path("slam-planner"), "--domain", domain, "--goal-store",
                          group.dir() + "/goals.json"});
  group.start("simulator", {testkit::bin_path("slam-simulator"), "--domain", domain, "--broker", broker,
                            "--world", kWorld, "--robots", std::to_string(kRobots), "--speed",
                            std::to_string(kSpeed), "--drift", "0", "--seed", "7", "--beams", "32"});

  auto world = sim::builtin_world(kWorld);
  ASSERT_TRUE(world) << world.message();

  auto participant = dds::Participant::create(lease.id(), "explore_test");
  ASSERT_TRUE(participant) << participant.message();
  Observer seen;
  auto snapshots = dds::make_reader(**participant, dds::kGridSnapshot,
                                    [&](const GridSnapshot& s, const auto&) { seen.on_snapshot(s); });
  ASSERT_TRUE(snapshots) << snapshots.message();
  auto states = dds::make_reader(**participant, dds::kRobotState,
                                 [&](const RobotState& s, const auto&) { seen.on_state(s); });
  ASSERT_TRUE(states) << states.message();
  auto paths = dds::make_reader(**participant, dds::kRobotPath,
                                [&](const RobotPath& p, const auto&) { seen.on_path(p); });
  ASSERT_TRUE(paths) << paths.message();
  auto truth = dds::make_reader(**participant, dds::kSimGroundTruth,
                                [&](const SimGroundTruth& t, const auto&) { seen.on_truth(t); });
  ASSERT_TRUE(truth) << truth.message();
  auto goals = dds::make_writer(**participant, dds::kNavGoal);
  ASSERT_TRUE(goals) << goals.message();

  ASSERT_TRUE(wait_until([&] { return seen.starts().size() >= static_cast<size_t>(kRobots); }, 60s))
      << "the robots never reached the gateway";
  ASSERT_TRUE(wait_until([&] { return seen.snapshots() > 0; }, 30s)) << "no grid snapshot from the mapper";
  ASSERT_TRUE((*goals)->wait_for_readers(30s)) << "the planner does not read goals";

  constexpr uint64_t kGoalId = 1;
  NavGoal goal;
  goal.robot_id("*");
  goal.goal_id(kGoalId);
  goal.mode(GOAL_EXPLORE);
  ASSERT_TRUE((*goals)->write(goal));
  const auto t0 = std::chrono::steady_clock::now();
  const auto elapsed_s = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };

  // Judge each new snapshot until the map is good enough or the budget is spent.
  const std::vector<Vec2> starts = seen.starts();
  testkit::MapScore best;
  double best_at_s = 0.0;
  size_t judged = seen.snapshots();
  while (std::chrono::steady_clock::now() - t0 < kBudget) {
    if (!wait_until([&] { return seen.snapshots() > judged; }, 5s)) continue;
    judged = seen.snapshots();
    const auto snapshot = seen.snapshot();
    const testkit::MapScore now = score(*world, *snapshot, starts);
    if (now.coverage() >= best.coverage()) {
      best = now;
      best_at_s = elapsed_s();
    }
    const auto [drift_m, drift_rad] = seen.drift();
    std::printf(
        "explore_test: %5.1f s: coverage %.3f (%zu of %zu cells), agreement %.3f (%zu of %zu), %d done, "
        "odometry off by up to %.2f m %.3f rad\n",
        elapsed_s(), now.coverage(), now.covered, now.reachable, now.agreement(), now.agreeing, now.observed,
        seen.finished(kGoalId), drift_m, drift_rad);
    if (now.coverage() >= kCoverageWanted || seen.finished(kGoalId) >= kRobots) break;
  }
  std::printf("explore_test: best coverage %.3f after %.1f s (agreement %.3f)\n", best.coverage(), best_at_s,
              best.agreement());
  EXPECT_GE(best.coverage(), kCoverageWanted);
  EXPECT_GE(best.agreement(), kAgreementWanted);
  EXPECT_TRUE(group.running("planner"));
  EXPECT_TRUE(group.running("mapper"));
}

}  // namespace
}  // namespace slam
