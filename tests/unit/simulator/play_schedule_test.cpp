// The log player's schedule: the start/end window, pieces, send times at a rate (held when stamps
// step back, paced at rate 0), and scans thinned and clipped into what one v2 scan carries.
#include "simulator/core/play_schedule.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace slam::sim {
namespace {

using robot_log::LaserScan;
using robot_log::RobotLog;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
constexpr double kPi = std::numbers::pi;

// Scans stamped 100, 100.5, 101, ... (one every 0.5 s).
RobotLog log_of(size_t scans) {
  RobotLog log;
  for (size_t i = 0; i < scans; ++i) {
    LaserScan s;
    s.stamp_s = 100 + 0.5 * static_cast<double>(i);
    s.odom = {static_cast<double>(i), 0, 0};
    log.scans.push_back(s);
  }
  return log;
}

TEST(PlaySchedule, WholeLogIsOnePiece) {
  const auto pieces = plan_pieces(log_of(10), 3, "intel", PlayOptions{});
  ASSERT_TRUE(pieces) << pieces.message();
  ASSERT_EQ(pieces->size(), 1u);
  EXPECT_EQ((*pieces)[0].robot_id, "intel");
  EXPECT_EQ((*pieces)[0].log, 3u);
  EXPECT_EQ((*pieces)[0].first, 0u);
  EXPECT_EQ((*pieces)[0].end, 10u);
}

TEST(PlaySchedule, StartAndEndCutAWindow) {
  PlayOptions o;
  o.start_s = 1.0;  // from the scan at 101 s
  o.end_s = 3.2;    // to the one at 103 s
  const auto pieces = plan_pieces(log_of(10), 0, "r", o);
  ASSERT_TRUE(pieces) << pieces.message();
  EXPECT_EQ((*pieces)[0].first, 2u);
  EXPECT_EQ((*pieces)[0].end, 7u);
  o.start_s = 20;
  o.end_s = 0;
  EXPECT_THAT(plan_pieces(log_of(10), 0, "r", o).message(), HasSubstr("0 scans"));
  EXPECT_THAT(plan_pieces(RobotLog{}, 0, "r", PlayOptions{}).message(), HasSubstr("no scans"));
}

TEST(PlaySchedule, PiecesSplitTheWindowIntoConsecutiveRobots) {
  PlayOptions o;
  o.pieces = 3;
  o.start_s = 0.5;  // scans 1..9
  const auto pieces = plan_pieces(log_of(10), 0, "aces", o);
  ASSERT_TRUE(pieces) << pieces.message();
  ASSERT_EQ(pieces->size(), 3u);
  EXPECT_EQ((*pieces)[0].robot_id, "aces-1");
  EXPECT_EQ((*pieces)[2].robot_id, "aces-3");
  EXPECT_EQ((*pieces)[0].first, 1u);
  EXPECT_EQ((*pieces)[0].end, (*pieces)[1].first);
  EXPECT_EQ((*pieces)[1].end, (*pieces)[2].first);
  EXPECT_EQ((*pieces)[2].end, 10u);
  EXPECT_EQ((*pieces)[0].size() + (*pieces)[1].size() + (*pieces)[2].size(), 9u);
  o.pieces = 20;
  EXPECT_THAT(plan_pieces(log_of(10), 0, "aces", o).message(), HasSubstr("fewer than 20 pieces"));
}

TEST(PlaySchedule, SendTimesFollowTheStampsAtTheRate) {
  RobotLog log = log_of(5);
  log.scans[3].stamp_s = 100.2;  // steps back: sent right after the scan before it
  const PlayPiece piece{"r", 0, 1, 5};
  EXPECT_THAT(send_times(log, piece, 1.0), ElementsAre(0.0, 0.5, 0.5, 1.5));
  EXPECT_THAT(send_times(log, piece, 2.0), ElementsAre(0.0, 0.25, 0.25, 0.75));
  EXPECT_THAT(send_times(log, piece, 0.0), ElementsAre(0.0, kFastPaceS, 2 * kFastPaceS, 3 * kFastPaceS));
  EXPECT_TRUE(send_times(log, PlayPiece{"r", 0, 2, 2}, 1.0).empty());
}

TEST(PlaySchedule, StampJumpsOfHoursAreNotWaitedOut) {
  // The clock jumps three hours ahead, later two hours back: each scan after a jump goes out right
  // after the one before it, and the log's spacing resumes from there. Neither hours of waiting
  // nor the rest of the log at once.
  RobotLog log = log_of(6);  // 100, 100.5, ... 102.5
  log.scans[2].stamp_s = 100.5 + 3 * 3600;
  log.scans[3].stamp_s = log.scans[2].stamp_s + 0.5;
  log.scans[4].stamp_s = log.scans[3].stamp_s - 2 * 3600;
  log.scans[5].stamp_s = log.scans[4].stamp_s + 0.5;
  EXPECT_THAT(send_times(log, PlayPiece{"r", 0, 0, 6}, 1.0), ElementsAre(0.0, 0.5, 0.5, 1.0, 1.0, 1.5));
  EXPECT_THAT(send_times(log, PlayPiece{"r", 0, 0, 6}, 2.0), ElementsAre(0.0, 0.25, 0.25, 0.5, 0.5, 0.75));
}

LaserScan scan_with(std::vector<float> ranges) {
  LaserScan s;
  s.stamp_s = 7.5;
  s.odom = {1, 2, 0.3};
  s.laser_in_robot = {0.04, 0, 0};
  s.angle_min_rad = -1.0;
  s.angle_increment_rad = 0.25;
  s.max_range_m = 10;
  s.ranges = std::move(ranges);
  return s;
}

TEST(PlaySchedule, EveryBeamByDefaultWithNoReturnsAtMaxRange) {
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const PlayedScan p = prepare_scan(scan_with({1, 12, 0, 2, inf, nan, -1, 10}), 0, 0);
  EXPECT_DOUBLE_EQ(p.stamp_s, 7.5);
  EXPECT_EQ(p.odom, (Pose{1, 2, 0.3}));
  EXPECT_EQ(p.sensor, (Pose{0.04, 0, 0}));
  EXPECT_DOUBLE_EQ(p.max_range, 10);
  // 0, NaN and -1 are error readings: left out. 12, inf and 10 are no return: sent as 10.
  EXPECT_THAT(p.angles, ElementsAre(-1.0, -0.75, -0.25, 0.0, 0.75));
  EXPECT_THAT(p.ranges, ElementsAre(1.0, 10.0, 2.0, 10.0, 10.0));
}

TEST(PlaySchedule, ClippingTurnsFarReadingsIntoNoReturns) {
  const PlayedScan p = prepare_scan(scan_with({1, 4, 5, 9}), 0, 4.5);
  EXPECT_DOUBLE_EQ(p.max_range, 4.5);
  EXPECT_THAT(p.ranges, ElementsAre(1.0, 4.0, 4.5, 4.5));
  EXPECT_DOUBLE_EQ(prepare_scan(scan_with({1}), 0, 20).max_range, 10);  // never beyond the sensor
}

TEST(PlaySchedule, ThinningKeepsEvenlySpacedBeams) {
  std::vector<float> ranges(180);
  for (size_t i = 0; i < ranges.size(); ++i) ranges[i] = 1.0f + 0.01f * static_cast<float>(i);
  LaserScan s = scan_with(ranges);
  s.angle_min_rad = -kPi / 2;
  s.angle_increment_rad = kPi / 180;
  const PlayedScan p = prepare_scan(s, 6, 0);
  ASSERT_EQ(p.angles.size(), 6u);
  // Sector centres: beams 15, 45, 75, 105, 135, 165 of 180 (-90..89 degrees): -75..75 by 30.
  for (size_t k = 0; k < 6; ++k) {
    EXPECT_NEAR(p.angles[k], (-75.0 + 30.0 * static_cast<double>(k)) * kPi / 180, 1e-12);
    EXPECT_FLOAT_EQ(static_cast<float>(p.ranges[k]), ranges[15 + 30 * k]);
  }
  EXPECT_EQ(prepare_scan(s, 1, 0).angles.size(), 1u);
  EXPECT_EQ(prepare_scan(s, 500, 0).angles.size(), 180u);  // more than there are: all
  EXPECT_TRUE(prepare_scan(scan_with({}), 5, 0).angles.empty());
}

}  // namespace
}  // namespace slam::sim
