// PoseCorrector under load: the pass budget, overflow by odometry, ties degraded and counted, the
// match worker, and a robot reset leaving the pose graph. Robots drive straight lines with a dozen
// obstacle points per message; the live grid is empty (tracking fails, which is irrelevant here):
// what is checked is how many keyframes each stage handles, not where they land.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "pose_correction/pose_corrector.hpp"

namespace slam::correction {
namespace {

constexpr int64_t kStepNs = 100'000'000;  // 10 Hz
constexpr double kStepM = 0.05;           // a keyframe (0.4 m) closes every 8 messages

struct EmptyMap {
  GridGeometry geometry{{-10, -10}, 0.05, 400, 400};
  std::vector<uint8_t> cells = std::vector<uint8_t>(geometry.cells(), 0);
  GridView view() const { return {geometry, cells}; }
};

std::vector<Vec2> wall_points() {
  std::vector<Vec2> hits;
  for (int i = 0; i < 12; ++i) hits.push_back({-0.6 + 0.1 * i, 1.0});
  return hits;
}

// `robot` drives `steps` messages along y = `y` from x = 0, starting at time step `first`; returns the
// keyframe ids its observations got.
std::vector<uint64_t> drive(PoseCorrector& corrector, const std::string& robot, int first, int steps,
                            double y = 0.0) {
  std::vector<uint64_t> ids;
  const auto hits = wall_points();
  for (int i = 0; i < steps; ++i) {
    auto id = corrector.add(robot, (first + i) * kStepNs, Pose{kStepM * i, y, 0.0}, true, hits);
    EXPECT_TRUE(id) << id.message();
    if (id) ids.push_back(*id);
  }
  return ids;
}

std::string robot_name(int r) {
  std::string name(1, 'r');  // (not "r" + ...: GCC 12 warns falsely about that concatenation)
  name += std::to_string(r);
  return name;
}

CorrectorOptions quiet_options() {
  CorrectorOptions o;
  o.old_age_s = 1.0;  // a robot's own keyframes a second old count as old map
  return o;
}

TEST(PoseCorrectorSchedule, ThePassBudgetBoundsEachPassAndTheRestFollowInOrder) {
  CorrectorOptions options = quiet_options();
  options.schedule.max_keyframes_per_pass = 3;
  PoseCorrector corrector(options);
  const EmptyMap map;
  for (int r = 0; r < 10; ++r) drive(corrector, robot_name(r), 0, 9);  // one keyframe each
  std::vector<KeyframeCorrection> finalised;
  corrector.process(map.view(), 9 * kStepNs, finalised);
  EXPECT_EQ(finalised.size(), 3u);
  EXPECT_EQ(corrector.stats().backlog, 7);
  for (int pass = 0; pass < 3; ++pass) corrector.process(map.view(), 9 * kStepNs, finalised);
  EXPECT_EQ(finalised.size(), 10u);
  EXPECT_EQ(corrector.stats().backlog, 0);
  EXPECT_TRUE(std::is_sorted(finalised.begin(), finalised.end(),
                             [](const auto& a, const auto& b) { return a.id < b.id; }));
  EXPECT_EQ(corrector.stats().placed_by_odometry, 0);
}

TEST(PoseCorrectorSchedule, ABacklogBeyondTheCapIsPlacedByOdometryAndCounted) {
  CorrectorOptions options = quiet_options();
  options.schedule.max_keyframes_per_pass = 2;
  options.schedule.max_backlog = 5;
  PoseCorrector corrector(options);
  const EmptyMap map;
  for (int r = 0; r < 10; ++r) drive(corrector, robot_name(r), 0, 9);
  std::vector<KeyframeCorrection> finalised;
  corrector.process(map.view(), 9 * kStepNs, finalised);
  EXPECT_EQ(corrector.stats().placed_by_odometry, 5);  // the oldest five, beyond the cap
  EXPECT_EQ(finalised.size(), 7u);                     // ...and the budget's two
  EXPECT_EQ(corrector.stats().backlog, 3);
  EXPECT_EQ(corrector.stats().keyframes, 7);
}

// Two robots drive the same line, the second three seconds behind: its keyframes find the first's
// (old map) around them and try ties. Returns the corrector's figures.
CorrectorStats follow(const CorrectorOptions& options) {
  PoseCorrector corrector(options);
  const EmptyMap map;
  std::vector<KeyframeCorrection> finalised;
  const auto hits = wall_points();
  for (int i = 0; i < 200; ++i) {
    for (const auto& [robot, lag] : {std::pair{"lead", 0}, std::pair{"follower", 30}}) {
      if (i < lag) continue;
      EXPECT_TRUE(corrector.add(robot, i * kStepNs, Pose{kStepM * (i - lag), 0.0, 0.0}, true, hits));
    }
    corrector.process(map.view(), i * kStepNs, finalised);
  }
  return corrector.stats();
}

TEST(PoseCorrectorSchedule, UnderLoadTiesAndWideSearchesAreRateLimitedAndCounted) {
  CorrectorOptions normal = quiet_options();
  const CorrectorStats all = follow(normal);
  EXPECT_GT(all.ties_tried, 10);
  EXPECT_EQ(all.ties_skipped, 0);
  EXPECT_EQ(all.wide_skipped, 0);

  CorrectorOptions loaded = quiet_options();
  loaded.schedule.load_backlog = 0;  // always loaded
  loaded.schedule.ties_every = 4;
  const CorrectorStats limited = follow(loaded);
  EXPECT_GT(limited.ties_skipped, 0);
  EXPECT_LT(limited.ties_tried + limited.wide_skipped, all.ties_tried);
  EXPECT_EQ(limited.keyframes, all.keyframes);  // every keyframe is still finalised

  CorrectorOptions shedding = loaded;
  shedding.schedule.shed_backlog = 0;
  const CorrectorStats tracking_only = follow(shedding);
  EXPECT_EQ(tracking_only.ties_tried, 0);
  EXPECT_EQ(tracking_only.closures_tried, 0);
  EXPECT_EQ(tracking_only.keyframes, all.keyframes);
}

TEST(PoseCorrectorSchedule, OnTheWorkerEveryKeyframeIsFinalisedInOrderPerRobot) {
  CorrectorOptions options = quiet_options();
  options.match_threads = 1;
  PoseCorrector corrector(options);
  const EmptyMap map;
  std::vector<KeyframeCorrection> finalised;
  std::set<uint64_t> ids;
  for (int r = 0; r < 4; ++r) {
    for (uint64_t id : drive(corrector, robot_name(r), 0, 40, r)) ids.insert(id);
  }
  const int64_t later = 40 * kStepNs + 10'000'000'000LL;  // long silence: open keyframes close
  for (int pass = 0; pass < 100000 && (finalised.size() < ids.size() || corrector.stats().backlog > 0);
       ++pass) {
    corrector.process(map.view(), later, finalised);
    // Sleep rather than yield: on a loaded machine the worker may need far longer than 100 000 yields.
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_EQ(finalised.size(), ids.size());
  for (const std::string robot : {"r0", "r1", "r2", "r3"}) {
    std::vector<uint64_t> order;
    for (const auto& k : finalised)
      if (k.robot == robot) order.push_back(k.id);
    EXPECT_TRUE(std::is_sorted(order.begin(), order.end())) << robot;
  }
  for (const auto& k : finalised) EXPECT_TRUE(ids.contains(k.id));
}

TEST(PoseCorrectorSchedule, AResetRobotLeavesThePoseGraphAndTheKeyframeIndex) {
  // Without a reset, the second robot's keyframes tie to the first's; after one, nothing is left
  // to tie to, and the graph holds only the second robot's keyframes.
  CorrectorOptions options = quiet_options();
  options.old_age_s = 60.0;  // only the other robot's keyframes count as old map
  for (const bool reset : {false, true}) {
    PoseCorrector corrector(options);
    const EmptyMap map;
    std::vector<KeyframeCorrection> finalised;
    drive(corrector, "first", 0, 80);
    corrector.process(map.view(), 80 * kStepNs + 10'000'000'000LL, finalised);
    const size_t first_keyframes = corrector.graph_keyframes();
    ASSERT_GE(first_keyframes, 9u);
    if (reset) {
      EXPECT_EQ(corrector.reset_robot("first"), first_keyframes);
      EXPECT_EQ(corrector.graph_keyframes(), 0u);
      EXPECT_EQ(corrector.reset_robot("never-seen"), 0u);
    }
    const int64_t start = 200;
    const auto hits = wall_points();
    for (int i = 0; i < 80; ++i) {
      ASSERT_TRUE(corrector.add("second", (start + i) * kStepNs, Pose{kStepM * i, 0.0, 0.0}, true, hits));
      corrector.process(map.view(), (start + i) * kStepNs, finalised);
    }
    SCOPED_TRACE(reset ? "reset" : "no reset");
    if (reset) {
      EXPECT_EQ(corrector.stats().ties_tried, 0);
      EXPECT_EQ(corrector.graph_keyframes(),
                static_cast<size_t>(corrector.stats().keyframes) - first_keyframes);
      EXPECT_EQ(corrector.stats().robots_reset, 1);
    } else {
      EXPECT_GT(corrector.stats().ties_tried, 0);
    }
  }
}

TEST(PoseCorrectorSchedule, AResetRobotStartsANewChainAndKeepsItsCorrection) {
  PoseCorrector corrector(quiet_options());
  const EmptyMap map;
  std::vector<KeyframeCorrection> finalised;
  drive(corrector, "r1", 0, 20);
  corrector.process(map.view(), 20 * kStepNs, finalised);
  ASSERT_TRUE(corrector.set_initial_pose("r1", {2.0, 3.0, 0.0}));
  const Pose before = corrector.correction("r1");
  corrector.reset_robot("r1");
  EXPECT_EQ(corrector.correction("r1"), before);
  finalised.clear();
  drive(corrector, "r1", 100, 20);
  corrector.process(map.view(), 120 * kStepNs, finalised);
  ASSERT_FALSE(finalised.empty());
  EXPECT_EQ(corrector.graph_keyframes(), finalised.size());
}

}  // namespace
}  // namespace slam::correction
