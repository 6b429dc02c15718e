// Bad input over a whole run (issue 37, item 7): a robot whose odometry jumps by 100 m mid-run
// while its stamps jump by hours, and a clock set back by hours. Each is counted, the jump starts a
// new trajectory segment, and the graph stays sane: nothing non-finite, the keyframes made before
// the jump stay where they were. Inline matching and blocking waits for the optimiser: deterministic.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <unordered_map>
#include <vector>

#include "pose_correction/pose_corrector.hpp"
#include "room_scene.hpp"

namespace slam::correction {
namespace {

constexpr int64_t kHour_ns = 3'600'000'000'000;
constexpr int64_t kMessage_ns = 100'000'000;  // 10 scans a second
constexpr double kStep_m = 0.05;              // 0.5 m/s

using testing_scene::cast;
using testing_scene::room;
using RoomMap = testing_scene::WallMap;

// A laser scan (120 beams, 4 m) taken at `truth`, its points in the odometry frame of `odom`.
std::vector<Vec2> scan(const Pose& truth, const Pose& odom) {
  const auto walls = room();
  std::vector<Vec2> hits;
  for (int i = 0; i < 120; ++i) {
    const double a = truth.theta + 2.0 * std::numbers::pi * i / 120.0;
    const Vec2 dir{std::cos(a), std::sin(a)};
    if (auto t = cast(walls, truth.position(), dir, 4.0)) {
      hits.push_back(odom.compose(truth.inverse()).transform(truth.position() + dir * *t));
    }
  }
  return hits;
}

// Every finalised keyframe's latest map pose (its correction applied to its odometry origin).
struct KeyframePoses {
  struct Entry {
    uint32_t segment = 0;
    Pose map;
  };
  std::unordered_map<uint64_t, Entry> by_id;
  void take(const std::vector<KeyframeCorrection>& corrections) {
    for (const KeyframeCorrection& k : corrections) by_id[k.id] = {k.segment, k.correction.compose(k.odom)};
  }
};

// A robot driving laps around the inner wall of the room; its odometry heading drifts a little.
class LapRun {
 public:
  explicit LapRun(const CorrectorOptions& options) : corrector_(options) {}

  // Drives `messages` messages; the stamp (arrival and the robot's own) advances kMessage_ns each.
  void drive(int messages) {
    static const std::vector<Vec2> corners{{1, 1}, {5, 1}, {5, 4.2}, {2.5, 4.2}, {2.5, 3}, {1, 3}};
    for (int m = 0; m < messages; ++m) {
      if (distance(truth_.position(), corners[corner_]) < 0.02) corner_ = (corner_ + 1) % corners.size();
      const Vec2 to = corners[corner_] - truth_.position();
      const double heading = std::atan2(to.y, to.x);
      const double d = std::min(kStep_m, norm(to));
      const Pose turn{0, 0, wrap_angle(heading - truth_.theta)};
      truth_ = Pose{truth_.x, truth_.y, heading}.compose(Pose{d, 0, 0});
      belief_ = belief_.compose(turn).compose(Pose{d, 0, 0.001});
      stamp_ns_ += kMessage_ns;
      const Pose odom = odom_shift_.compose(belief_);
      ASSERT_TRUE(corrector_.add("r1", stamp_ns_, odom, true, scan(truth_, odom), stamp_ns_));
      process();
      worst_error_m_ = std::max(worst_error_m_, error_m());
    }
  }
  void process() {
    finalised_.clear();
    corrector_.process(map_.view(), stamp_ns_, finalised_);
    poses_.take(finalised_);
    if (!corrector_.optimising()) return;
    corrector_.wait_for_optimisation();
    finalised_.clear();
    (void)corrector_.take_optimised(finalised_);
    poses_.take(finalised_);
  }
  // Closes the open keyframe and settles the final optimisation.
  void finish() {
    corrector_.finish();
    for (int i = 0; i < 3; ++i) {
      process();
      corrector_.wait_for_optimisation();
    }
    process();
  }
  // How far the corrected pose is from the truth now.
  double error_m() const {
    return distance(corrector_.correction("r1").compose(odom_shift_.compose(belief_)).position(),
                    truth_.position());
  }

  PoseCorrector& corrector() { return corrector_; }
  const KeyframePoses& poses() const { return poses_; }
  Pose& odom_shift() { return odom_shift_; }
  int64_t& stamp_ns() { return stamp_ns_; }
  const Pose& truth() const { return truth_; }
  double worst_error_m() const { return worst_error_m_; }
  void reset_worst_error() { worst_error_m_ = 0.0; }

 private:
  PoseCorrector corrector_;
  RoomMap map_{room()};
  Pose truth_{1, 1, 0};
  Pose belief_{1, 1, 0};
  Pose odom_shift_;  // what the odometry adds to the robot's belief (its jump)
  size_t corner_ = 1;
  int64_t stamp_ns_ = 1'000'000'000;
  double worst_error_m_ = 0.0;
  std::vector<KeyframeCorrection> finalised_;
  KeyframePoses poses_;
};

bool finite(const Eigen::Matrix3d& m) {
  return m.allFinite();
}

CorrectorOptions options() {
  CorrectorOptions o;
  o.old_age_s = 20.0;  // a lap (14.4 m) takes 29 s: the second lap ties to the first
  return o;
}

TEST(PoseCorrectorBadInput, AHundredMetreOdometryJumpAndHoursOfStampsStartANewSegment) {
  LapRun run(options());
  run.drive(450);  // a lap and a half
  run.finish();
  const KeyframePoses before = run.poses();
  ASSERT_GT(before.by_id.size(), 50u);
  EXPECT_LT(run.worst_error_m(), 0.1);
  EXPECT_EQ(run.corrector().stats().segments, 0);

  // Mid-run the odometry jumps 100 m (a reset, a glitch) and the stamps jump three hours.
  run.odom_shift() = Pose{100.0, 0.0, 0.0};
  run.stamp_ns() += 3 * kHour_ns;
  run.drive(300);
  run.finish();

  const CorrectorStats& stats = run.corrector().stats();
  EXPECT_EQ(stats.segments, 1);
  EXPECT_EQ(stats.rejected_inputs, 0);
  EXPECT_EQ(stats.clock_steps, 0);  // forward: nothing to take out
  // The keyframes before the jump stay in segment 0 and where they were; the ones after are in
  // segment 1, every pose finite.
  double largest_move = 0.0;
  size_t after_jump = 0;
  for (const auto& [id, entry] : run.poses().by_id) {
    EXPECT_TRUE(is_finite(entry.map)) << "keyframe " << id;
    const auto old = before.by_id.find(id);
    if (old == before.by_id.end()) {
      EXPECT_EQ(entry.segment, 1u) << "keyframe " << id;
      ++after_jump;
      continue;
    }
    EXPECT_EQ(entry.segment, 0u) << "keyframe " << id;
    largest_move = std::max(largest_move, distance(old->second.map.position(), entry.map.position()));
  }
  RecordProperty("largest_move_mm", static_cast<int>(largest_move * 1000));
  EXPECT_GT(after_jump, 30u);
  EXPECT_LT(largest_move, 0.03);
  // The robot's correction and its uncertainty stay finite; the new segment is barely known.
  EXPECT_TRUE(is_finite(run.corrector().correction("r1")));
  std::vector<RobotCorrection> changed;
  run.corrector().take_changed(changed);
  ASSERT_FALSE(changed.empty());
  EXPECT_EQ(changed.back().segment, 1u);
  EXPECT_TRUE(finite(changed.back().covariance));
  EXPECT_TRUE(is_finite(changed.back().map_from_odom));
}

TEST(PoseCorrectorBadInput, AClockSetBackByHoursStillTiesTheRobotToItsOldMap) {
  // A lap, then the clock (arrival and the robot's) is set back five hours and the robot drives
  // a second lap over the first. Its first lap is still old map to it: the second lap ties to it.
  LapRun run(options());
  run.drive(300);
  const int64_t ties_before = run.corrector().stats().ties_tried;
  run.stamp_ns() -= 5 * kHour_ns;
  run.reset_worst_error();
  run.drive(300);
  run.finish();
  const CorrectorStats& stats = run.corrector().stats();
  EXPECT_EQ(stats.clock_steps, 2);  // the observations' stamps and process()'s clock
  EXPECT_EQ(stats.segments, 0);
  EXPECT_GT(stats.ties_tried - ties_before, 30);
  EXPECT_GT(stats.optimisations, 0);
  EXPECT_LT(run.worst_error_m(), 0.1);
  for (const auto& [id, entry] : run.poses().by_id) EXPECT_TRUE(is_finite(entry.map)) << "keyframe " << id;
}

}  // namespace
}  // namespace slam::correction
