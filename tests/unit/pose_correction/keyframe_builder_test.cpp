#include "pose_correction/keyframe_builder.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace slam::correction {
namespace {

constexpr int64_t kStep = 100'000'000;  // 10 Hz

TEST(KeyframeBuilder, ClosesAfterTheConfiguredTravelWithPointsInItsOwnFrame) {
  KeyframeOptions options;
  options.travel_m = 0.4;
  KeyframeBuilder builder(options);
  const std::vector<Vec2> hit{{2.0, 1.0}};
  // A robot heading +y (90 deg) at (1, 0), driving 0.05 m per message.
  KeyframeBuilder::Step step = KeyframeBuilder::Step::Added;
  int messages = 0;
  for (; step == KeyframeBuilder::Step::Added; ++messages) {
    const Pose pose{1.0, 0.05 * messages, 1.5707963267948966};
    step = builder.add(7, 0, messages * kStep, pose, true, hit);
  }
  EXPECT_EQ(step, KeyframeBuilder::Step::AddedAndClosed);
  EXPECT_EQ(messages, 9);  // 0.40 m after the eighth step
  const Keyframe k = builder.take();
  EXPECT_FALSE(builder.open());
  EXPECT_EQ(k.id, 7u);
  EXPECT_EQ(k.messages, 9);
  EXPECT_NEAR(k.travel_m, 0.4, 1e-9);  // how far it got from the origin
  EXPECT_NEAR(k.turn_rad, 0.0, 1e-12);
  ASSERT_EQ(k.points.size(), 9u);
  // (2, 1) seen from (1, 0) heading +y lies 1 m ahead and 1 m to the right.
  EXPECT_NEAR(k.points[0].x, 1.0, 1e-12);
  EXPECT_NEAR(k.points[0].y, -1.0, 1e-12);
}

TEST(KeyframeBuilder, AKeyframeOfLaserScansHoldsTheScansOfAShortMove) {
  KeyframeOptions options;  // scan_points 60, scan_travel_m 0.1
  KeyframeBuilder scans(options);
  KeyframeBuilder sparse(options);
  const std::vector<Vec2> scan(options.scan_points, Vec2{2.0, 1.0});
  const std::vector<Vec2> few(options.scan_points - 1, Vec2{2.0, 1.0});
  int scan_messages = 0, sparse_messages = 0;
  auto step = KeyframeBuilder::Step::Added;
  for (; step == KeyframeBuilder::Step::Added; ++scan_messages)
    step = scans.add(1, 0, scan_messages * kStep, Pose{0.04 * scan_messages, 0.0, 0.0}, true, scan);
  // The scan at 0.12 m is beyond the keyframe: it starts the next one, not carried into this one.
  EXPECT_EQ(step, KeyframeBuilder::Step::StartsNext);
  EXPECT_EQ(scan_messages, 4);
  const Keyframe first = scans.take();
  EXPECT_TRUE(first.scans);
  EXPECT_EQ(first.messages, 3);
  EXPECT_NEAR(first.travel_m, 0.08, 1e-9);
  EXPECT_EQ(scans.add(2, 0, 3 * kStep, Pose{0.12, 0.0, 0.0}, true, scan), KeyframeBuilder::Step::Added);
  EXPECT_NEAR(scans.take().odom.x, 0.12, 1e-12);

  for (auto sparse_step = KeyframeBuilder::Step::Added; sparse_step == KeyframeBuilder::Step::Added;
       ++sparse_messages)
    sparse_step =
        sparse.add(1, 0, sparse_messages * kStep, Pose{0.04 * sparse_messages, 0.0, 0.0}, true, few);
  EXPECT_EQ(sparse_messages, 11);  // the sparse limit: 0.40 m, that message included
  EXPECT_FALSE(sparse.take().scans);

  // Standing still, scans keep joining one keyframe until the message limit.
  int standing = 0;
  for (step = KeyframeBuilder::Step::Added; step == KeyframeBuilder::Step::Added; ++standing)
    step = scans.add(3, 0, standing * kStep / 100, Pose{}, true, scan);
  EXPECT_EQ(step, KeyframeBuilder::Step::AddedAndClosed);
  EXPECT_EQ(standing, options.max_messages);
}

TEST(KeyframeBuilder, TurningEveryScanBeyondTheTurnLimitIsAKeyframeOfItsOwn) {
  KeyframeOptions options;  // scan_turn_rad 0.0125
  KeyframeBuilder builder(options);
  const std::vector<Vec2> scan(options.scan_points, Vec2{2.0, 1.0});
  // Turning on the spot at 6 deg per scan, as a 5 Hz scanner sees a robot turn at 30 deg/s: odometry
  // never has to carry one scan to another inside a keyframe.
  int keyframes = 0;
  for (int i = 0; i < 10; ++i) {
    const Pose pose{0.0, 0.0, 0.1 * i};
    auto step = builder.add(static_cast<uint64_t>(i), 0, i * kStep, pose, true, scan);
    if (step == KeyframeBuilder::Step::StartsNext) {
      const Keyframe k = builder.take();
      EXPECT_EQ(k.messages, 1);
      ++keyframes;
      step = builder.add(static_cast<uint64_t>(i), 0, i * kStep, pose, true, scan);
    }
    EXPECT_EQ(step, KeyframeBuilder::Step::Added);
  }
  EXPECT_EQ(keyframes, 9);
}

TEST(KeyframeBuilder, TheRobotsOwnStampsMeasureTheSpan) {
  // A robot standing still sends one message a second; they arrive bunched (a log played fast): the
  // keyframe spans 4 s of the robot's time, not of arrival.
  KeyframeBuilder builder(KeyframeOptions{});  // max_span_ns 4 s
  const std::vector<Vec2> hit{{2.0, 1.0}};
  int messages = 0;
  for (auto step = KeyframeBuilder::Step::Added; step == KeyframeBuilder::Step::Added; ++messages)
    step = builder.add(1, 0, 1000 + messages, Pose{}, true, hit, int64_t{messages} * 1'000'000'000);
  EXPECT_EQ(messages, 5);
  EXPECT_FALSE(builder.stale(1000 + messages));  // staleness stays on the arrival clock
}

TEST(KeyframeBuilder, ARobotClockSetBackClosesTheKeyframe) {
  // The robot's stamps go back two hours (its clock was set): how long the keyframe spans is
  // unknown, it closes; the next one starts on the new clock. A small step back (a log's stamps
  // out of order by a second) changes nothing.
  KeyframeBuilder builder(KeyframeOptions{});
  const std::vector<Vec2> hit{{2.0, 1.0}};
  constexpr int64_t kT = 10'000'000'000'000;
  ASSERT_EQ(builder.add(1, 0, 0, Pose{}, true, hit, kT), KeyframeBuilder::Step::Added);
  EXPECT_EQ(builder.add(1, 0, kStep, Pose{}, true, hit, kT - 1'000'000'000), KeyframeBuilder::Step::Added);
  EXPECT_EQ(builder.add(1, 0, 2 * kStep, Pose{}, true, hit, kT - 7'200'000'000'000),
            KeyframeBuilder::Step::AddedAndClosed);
  EXPECT_EQ(builder.take().messages, 3);
  EXPECT_EQ(builder.add(2, 0, 3 * kStep, Pose{}, true, hit, kT - 7'199'900'000'000),
            KeyframeBuilder::Step::Added);
  EXPECT_EQ(builder.segment(), 0u);  // the odometry did not jump
}

TEST(KeyframeBuilder, RobotsWithoutHeadingKeepTheOdometryAxes) {
  KeyframeBuilder builder(KeyframeOptions{});
  const std::vector<Vec2> hit{{3.0, 4.0}};
  ASSERT_EQ(builder.add(1, 0, 0, {1.0, 1.0, 2.0}, false, hit), KeyframeBuilder::Step::Added);
  const Keyframe k = builder.take();
  EXPECT_EQ(k.odom.theta, 0.0);
  EXPECT_NEAR(k.points[0].x, 2.0, 1e-12);
  EXPECT_NEAR(k.points[0].y, 3.0, 1e-12);
}

TEST(KeyframeBuilder, ClosesAfterMaxMessagesWhenStandingStill) {
  KeyframeOptions options;
  options.max_messages = 5;
  KeyframeBuilder builder(options);
  for (int i = 0; i < 4; ++i)
    EXPECT_EQ(builder.add(1, 0, i * kStep, {}, true, {}), KeyframeBuilder::Step::Added);
  EXPECT_EQ(builder.add(1, 0, 4 * kStep, {}, true, {}), KeyframeBuilder::Step::AddedAndClosed);
  const Keyframe k = builder.take();
  EXPECT_EQ(k.travel_m, 0.0);  // the corrector places such a keyframe by odometry
  EXPECT_EQ(k.turn_rad, 0.0);
}

TEST(KeyframeBuilder, AnOdometryJumpStartsANewSegment) {
  KeyframeBuilder builder(KeyframeOptions{});
  ASSERT_EQ(builder.add(1, 0, 0, {0.0, 0.0, 0.0}, true, {}), KeyframeBuilder::Step::Added);
  // 5 m in 0.1 s: a reset or a teleport, not a motion.
  EXPECT_EQ(builder.add(2, 0, kStep, {5.0, 0.0, 0.0}, true, {}), KeyframeBuilder::Step::Jump);
  EXPECT_EQ(builder.take().segment, 0u);
  EXPECT_EQ(builder.add(2, 0, kStep, {5.0, 0.0, 0.0}, true, {}), KeyframeBuilder::Step::Added);
  EXPECT_EQ(builder.segment(), 1u);
  const Keyframe k = builder.take();
  EXPECT_EQ(k.segment, 1u);
  EXPECT_EQ(k.odom.x, 5.0);
}

TEST(KeyframeBuilder, ASilentRobotsKeyframeGoesStale) {
  KeyframeOptions options;
  options.max_span_ns = 2'000'000'000;
  KeyframeBuilder builder(options);
  ASSERT_EQ(builder.add(1, 0, 0, {}, true, {}), KeyframeBuilder::Step::Added);
  EXPECT_FALSE(builder.stale(1'000'000'000));
  EXPECT_TRUE(builder.stale(2'000'000'000));
}

}  // namespace
}  // namespace slam::correction
