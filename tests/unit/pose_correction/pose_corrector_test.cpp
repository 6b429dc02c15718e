#include "pose_correction/pose_corrector.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <optional>
#include <random>
#include <vector>

#include "room_scene.hpp"

namespace slam::correction {
namespace {

using testing_scene::cast;
using testing_scene::room;
using testing_scene::Wall;
using TrueMap = testing_scene::WallMap;

// Sparse sensing: 10 beams over 360 degrees, 4 m range, each range off by `range_noise` (metres, or
// none); hits given in the robot's belief frame.
std::vector<Vec2> sense(const std::vector<Wall>& walls, const Pose& truth, const Pose& belief, int phase,
                        std::normal_distribution<double>* range_noise = nullptr,
                        std::mt19937* rng = nullptr) {
  std::vector<Vec2> hits;
  for (int i = 0; i < 10; ++i) {
    const double a = truth.theta + 2.0 * std::numbers::pi * (i + 0.37 * phase) / 10.0;
    const Vec2 dir{std::cos(a), std::sin(a)};
    if (auto t = cast(walls, truth.position(), dir, 4.0)) {
      const double range = range_noise ? *t + (*range_noise)(*rng) : *t;
      const Vec2 world = truth.position() + dir * range;
      // The robot computes its points with its own pose belief.
      hits.push_back(belief.compose(truth.inverse()).transform(world));
    }
  }
  return hits;
}

struct Drive {
  double worst_raw = 0.0;        // m, odometry against the truth
  double worst_corrected = 0.0;  // m, the corrected pose against the truth (after the first 20 messages)
  double rms_corrected = 0.0;
};

// A rectangle loop around the inner wall, 0.03 m per message, driven twice, on the known map; the
// odometry heading drifts `heading_drift` rad per message; ranges are off by `range_sigma` (metres).
// `after_process` (optional) runs after every process() with the robot's odometry pose.
Drive drive_two_laps(PoseCorrector& corrector, const TrueMap& map, double heading_drift, double range_sigma,
                     std::vector<KeyframeCorrection>& finalised,
                     const std::function<void(const Pose&)>& after_process = {}) {
  std::mt19937 rng(11);
  std::normal_distribution<double> range_noise(0.0, range_sigma);
  const auto walls = room();
  std::vector<Vec2> corners{{1, 1}, {5, 1}, {5, 4.2}, {2.5, 4.2}, {2.5, 3}, {1, 3}};
  Pose truth{1, 1, 0};
  Pose belief = truth;
  Drive result;
  double squared_sum = 0.0;
  int samples = 0;
  int64_t stamp = 0;
  int step = 0;
  for (int lap = 0; lap < 2; ++lap) {
    for (size_t c = 0; c < corners.size(); ++c) {
      const Vec2 target = corners[(c + 1) % corners.size()];
      while (distance(truth.position(), target) > 0.02) {
        const Vec2 to = target - truth.position();
        const double heading = std::atan2(to.y, to.x);
        const double d = std::min(0.03, norm(to));
        const Pose motion{d, 0.0, 0.0};
        const Pose turned_truth{truth.x, truth.y, heading};
        const Pose relative = Pose{0, 0, wrap_angle(heading - truth.theta)};
        truth = turned_truth.compose(motion);
        belief = belief.compose(relative).compose(Pose{d, 0.0, heading_drift});
        stamp += 100'000'000;
        ++step;
        const auto hits = sense(walls, truth, belief, step, range_sigma > 0.0 ? &range_noise : nullptr, &rng);
        EXPECT_TRUE(corrector.add("r1", stamp, belief, true, hits));
        corrector.process(map.view(), stamp, finalised);
        if (after_process) after_process(belief);
        const Pose corrected = corrector.correction("r1").compose(belief);
        result.worst_raw = std::max(result.worst_raw, distance(belief.position(), truth.position()));
        if (step > 20) {
          const double error = distance(corrected.position(), truth.position());
          result.worst_corrected = std::max(result.worst_corrected, error);
          squared_sum += error * error;
          ++samples;
        }
      }
    }
  }
  result.rms_corrected = std::sqrt(squared_sum / samples);
  return result;
}

TEST(PoseCorrector, CorrectionKeepsADriftingRobotOnAKnownMap) {
  const TrueMap map(room());
  PoseCorrector corrector;
  std::vector<KeyframeCorrection> finalised;
  // 0.0015 rad per message: about 9 degrees per lap.
  const Drive d = drive_two_laps(corrector, map, 0.0015, 0.0, finalised);
  RecordProperty("worst_raw_mm", static_cast<int>(d.worst_raw * 1000));
  RecordProperty("worst_corrected_mm", static_cast<int>(d.worst_corrected * 1000));
  EXPECT_GT(d.worst_raw, 0.5);         // the drift is real...
  EXPECT_LT(d.worst_corrected, 0.08);  // ...and the correction holds the robot on the map
  EXPECT_GT(corrector.stats().matched, corrector.stats().keyframes / 2);
  EXPECT_FALSE(finalised.empty());
}

TEST(PoseCorrector, ExactOdometryIsTrustedAndBarelyMovedByMatchNoise) {
  const TrueMap map(room());
  PoseCorrector corrector;
  std::vector<KeyframeCorrection> finalised;
  const Drive d = drive_two_laps(corrector, map, 0.0, 0.05, finalised);
  RecordProperty("rms_corrected_um", static_cast<int>(d.rms_corrected * 1e6));
  RecordProperty("worst_corrected_um", static_cast<int>(d.worst_corrected * 1e6));
  EXPECT_EQ(d.worst_raw, 0.0);
  EXPECT_GT(corrector.stats().matched, corrector.stats().keyframes / 2);  // the matches were there...
  // ...but the robot's odometry, learned to be exact, keeps most of their noise (5 cm of range
  // noise) out of its pose: 3.1 / 7.5 mm here. Tracking takes a match at half its response's
  // variance (CorrectorOptions::track_variance_scale); at the full variance this was 2.7 / 4.8 mm,
  // and 3.7 / 9.0 mm when every match was fused at the nominal odometry model.
  EXPECT_LT(d.rms_corrected, 0.0035);
  EXPECT_LT(d.worst_corrected, 0.0085);
}

TEST(PoseCorrector, AnOptimisationLeavesATrackedAndTiedRobotWhereItIs) {
  // In its second lap the robot is tied to its first lap's keyframes all along, and a graph
  // optimisation runs every five ties. Tracking and the ties set each keyframe's estimate; the
  // graph's sequential edges are the motions tracking measured, so a solve agrees with the
  // estimates and barely moves the robot. (With the bare odometry as the edge of every tied
  // keyframe, each solve pulled the chain towards the drifting odometry, moving the robot 4.5 cm.)
  const TrueMap map(room());
  CorrectorOptions options;
  options.optimise_every = 5;
  options.old_age_s = 30.0;
  // The walls' heading off: a heading edge per keyframe lets the solve revise past headings (a
  // smoother), which a filter's estimates never are, so with it a solve does move the robot.
  options.wall_heading = false;
  PoseCorrector corrector(options);
  std::vector<KeyframeCorrection> finalised, moved;
  double largest_move = 0.0;
  int landed = 0;
  drive_two_laps(corrector, map, 0.0015, 0.0, finalised, [&](const Pose& odometry) {
    if (!corrector.optimising()) return;
    corrector.wait_for_optimisation();
    const Vec2 before = corrector.correction("r1").transform(odometry.position());
    moved.clear();
    (void)corrector.take_optimised(moved);
    const Vec2 after = corrector.correction("r1").transform(odometry.position());
    largest_move = std::max(largest_move, distance(before, after));
    ++landed;
  });
  RecordProperty("largest_move_mm", static_cast<int>(largest_move * 1000));
  EXPECT_GE(landed, 5);
  EXPECT_LT(largest_move, 0.015);
}

TEST(PoseCorrector, ARobotStandingStillIsNeitherMatchedNorMoved) {
  // Drives 1.5 m along the room, stands still for 20 s (as a robot waiting for another does), then
  // drives on. While it stands its keyframes see what the last one saw: they are placed by odometry,
  // and its correction does not change.
  const TrueMap map(room());
  PoseCorrector corrector;
  std::vector<KeyframeCorrection> finalised;
  const auto walls = room();
  Pose truth{1, 1, 0};
  int64_t stamp = 0;
  int step = 0;
  auto send = [&](const Pose& pose) {
    stamp += 100'000'000;
    ++step;
    ASSERT_TRUE(corrector.add("r1", stamp, pose, true, sense(walls, pose, pose, step)));
    corrector.process(map.view(), stamp, finalised);
  };
  for (int i = 0; i < 50; ++i) {
    truth = truth.compose(Pose{0.03, 0.0, 0.0});
    send(truth);
  }
  // The keyframe open when it stopped, and the next (whose origin lies before the stop), moved.
  for (int i = 0; i < 70; ++i) send(truth);
  const int64_t matched_before = corrector.stats().matched;
  const int64_t standing_before = corrector.stats().standing;
  EXPECT_GT(matched_before, 0);
  const Pose correction_standing = corrector.correction("r1");
  for (int i = 0; i < 150; ++i) send(truth);
  EXPECT_GE(corrector.stats().standing - standing_before, 4);  // a keyframe every 30 messages
  EXPECT_EQ(corrector.stats().matched, matched_before);
  EXPECT_EQ(corrector.correction("r1"), correction_standing);
  EXPECT_EQ(corrector.stats().unmatched, 0);  // standing is not a failed match
  for (int i = 0; i < 40; ++i) {
    truth = truth.compose(Pose{0.03, 0.0, 0.0});
    send(truth);
  }
  EXPECT_GT(corrector.stats().matched, matched_before);  // matched again once it moves
}

TEST(PoseCorrector, ASlowTurnInKeyframesOfAScanEachIsNotStanding) {
  // A laser robot turns on the spot at 0.7 deg per scan: each scan is a keyframe of its own
  // (scan_turn_rad), each within the standing limits of the one before. Standing is judged
  // against the last keyframe matched, so the turn is matched, not left to odometry.
  const TrueMap map(room());
  PoseCorrector corrector;
  std::vector<KeyframeCorrection> finalised;
  const auto walls = room();
  int64_t stamp = 0;
  for (int i = 0; i < 60; ++i) {
    const Pose pose{3.0, 1.0, 0.012 * i};
    stamp += 100'000'000;
    ASSERT_TRUE(corrector.add("r1", stamp, pose, true, testing_scene::laser_hits(walls, pose, pose)));
    corrector.process(map.view(), stamp, finalised);
  }
  EXPECT_GE(corrector.stats().matched, 25);  // judged against the previous keyframe: 1
  EXPECT_LE(corrector.stats().standing, corrector.stats().matched);
}

TEST(PoseCorrector, ARobotWhoseOdometryStartsFarAwayStartsAtTheOrigin) {
  PoseCorrector corrector;
  const std::vector<Vec2> hits{{601.0, -200.0}};
  ASSERT_TRUE(corrector.add("far", 1, Pose{600.0, -200.0, 0.5}, true, hits));
  const Pose c = corrector.correction("far");
  EXPECT_NEAR(c.compose(Pose{600.0, -200.0, 0.5}).x, 0.0, 1e-9);
  EXPECT_NEAR(c.compose(Pose{600.0, -200.0, 0.5}).y, 0.0, 1e-9);
  EXPECT_NEAR(c.theta, 0.0, 1e-12);  // heading kept
  ASSERT_TRUE(corrector.add("near", 1, Pose{30.0, 4.0, 0.0}, true, hits));
  EXPECT_EQ(corrector.correction("near"), Pose{});  // within far_start_m: the odometry frame as it is
}

TEST(PoseCorrector, TheObserverSeesEveryKeyframeWhereItWasPlaced) {
  const TrueMap map(room());
  PoseCorrector corrector;
  std::vector<KeyframeDecision> decisions;
  corrector.set_keyframe_observer([&](const KeyframeDecision& k) {
    decisions.push_back(k);
    decisions.back().robot = {};  // the view is only valid during the call
    EXPECT_EQ(k.robot, "r1");
  });
  std::vector<KeyframeCorrection> finalised;
  drive_two_laps(corrector, map, 0.0015, 0.0, finalised);
  ASSERT_EQ(decisions.size(), finalised.size());
  ASSERT_EQ(static_cast<int64_t>(decisions.size()), corrector.stats().keyframes);
  int matched = 0, tied = 0;
  for (size_t i = 0; i < decisions.size(); ++i) {
    const KeyframeDecision& k = decisions[i];
    // Placed where the keyframe's correction puts its odometry origin.
    const Pose placed = finalised[i].correction.compose(finalised[i].odom);
    EXPECT_NEAR(k.estimate.x, placed.x, 1e-9);
    EXPECT_NEAR(k.estimate.y, placed.y, 1e-9);
    EXPECT_NEAR(wrap_angle(k.estimate.theta - placed.theta), 0.0, 1e-9);
    if (i > 0) {
      EXPECT_GT(k.stamp_ns, decisions[i - 1].stamp_ns);
    }
    matched += k.match ? 1 : 0;
    tied += k.tied ? 1 : 0;
    if (k.match) {
      EXPECT_GT(k.match_covariance(0, 0), 0.0);
    }
  }
  EXPECT_EQ(matched, corrector.stats().matched);
  EXPECT_GT(tied, 0);  // the second lap is tied to the first
}

TEST(PoseCorrector, TheRobotsUncertaintyGrowsUntilItIsTiedToTheOldMap) {
  const TrueMap map(room());
  PoseCorrector corrector;
  std::vector<double> sigmas;  // position sigma after each keyframe
  std::vector<bool> tied;
  corrector.set_keyframe_observer([&](const KeyframeDecision& k) {
    sigmas.push_back(std::sqrt(k.uncertainty(0, 0) + k.uncertainty(1, 1)));
    tied.push_back(k.tied);
  });
  // What its correction carries (PoseCorrection.covariance; exploring robots go by it).
  std::vector<double> published;
  std::vector<RobotCorrection> changed;
  std::vector<KeyframeCorrection> finalised;
  drive_two_laps(corrector, map, 0.0015, 0.0, finalised, [&](const Pose&) {
    changed.clear();
    corrector.take_changed(changed);
    for (const RobotCorrection& c : changed) {
      published.push_back(std::sqrt(std::max(c.covariance(0, 0), c.covariance(1, 1))));
    }
  });
  // The first lap has no old map to tie to: tracking against its own fresh trail does not make
  // the robot surer of where it is, every step of odometry adds to it.
  const auto first_tie = std::find(tied.begin() + 1, tied.end(), true) - tied.begin();
  ASSERT_LT(first_tie, static_cast<long>(tied.size()));
  ASSERT_GT(first_tie, 5);
  for (long i = 1; i < first_tie; ++i) EXPECT_GT(sigmas[i], sigmas[i - 1]) << "keyframe " << i;
  EXPECT_LT(sigmas[first_tie], 0.1 * sigmas[first_tie - 1]);  // the tie to the first lap shrinks it
  // Closures are judged against a chain that starts barely known (2 m); the published uncertainty
  // starts at the trusted start's few centimetres instead, grows the same way and shrinks with the
  // ties.
  EXPECT_GT(sigmas.front(), 1.0);
  ASSERT_GE(published.size(), static_cast<size_t>(first_tie));
  EXPECT_LT(published.front(), 0.06);
  const double most = *std::max_element(published.begin(), published.end());
  EXPECT_GT(most, 2.0 * published.front());
  EXPECT_LT(most, 1.0);
  EXPECT_LT(published.back(), 0.5 * most);
}

TEST(PoseCorrector, TheWallsHoldTheHeadingOfARobotWithNoMapToMatch) {
  // No map at all (every match fails, as far out in new ground), 9 degrees of heading drift a lap:
  // odometry alone walks the robot off, the walls' directions hold its heading.
  const TrueMap nothing(std::vector<Wall>{});
  const auto drive = [&](bool walls) {
    CorrectorOptions options;
    options.wall_heading = walls;
    PoseCorrector corrector(options);
    std::vector<KeyframeCorrection> finalised;
    const Drive d = drive_two_laps(corrector, nothing, 0.0003, 0.01, finalised);
    return std::pair{d, corrector.stats()};
  };
  const auto [without, without_stats] = drive(false);
  const auto [with, with_stats] = drive(true);
  RecordProperty("worst_without_mm", static_cast<int>(without.worst_corrected * 1000));
  RecordProperty("worst_with_mm", static_cast<int>(with.worst_corrected * 1000));
  EXPECT_EQ(without_stats.wall_headings, 0);
  EXPECT_GT(with_stats.wall_headings, with_stats.keyframes / 2);
  EXPECT_GT(without.worst_corrected, 0.5);
  EXPECT_LT(with.worst_corrected, 0.25 * without.worst_corrected);
}

TEST(PoseCorrector, WallsAtManyAnglesCorrectNoHeading) {
  // A heptagonal room: its walls share no pair of perpendicular directions, so the map never gets
  // axes and no keyframe's heading is pulled toward one.
  std::vector<Wall> heptagon;
  const Vec2 centre{3.0, 2.5};
  for (int i = 0; i < 7; ++i) {
    const double a0 = 2.0 * std::numbers::pi * i / 7.0, a1 = 2.0 * std::numbers::pi * (i + 1) / 7.0;
    heptagon.push_back({centre + Vec2{2.4 * std::cos(a0), 2.4 * std::sin(a0)},
                        centre + Vec2{2.4 * std::cos(a1), 2.4 * std::sin(a1)}});
  }
  const TrueMap map(heptagon);
  PoseCorrector corrector;
  std::vector<KeyframeCorrection> finalised;
  int64_t stamp = 0;
  for (int step = 0; step < 1200; ++step) {  // three laps of a 1 m circle
    const double a = 2.0 * std::numbers::pi * step / 400.0;
    const Pose truth{centre.x + std::cos(a), centre.y + std::sin(a), a + std::numbers::pi / 2.0};
    stamp += 100'000'000;
    ASSERT_TRUE(corrector.add("r1", stamp, truth, true, sense(heptagon, truth, truth, step)));
    corrector.process(map.view(), stamp, finalised);
  }
  EXPECT_GT(corrector.stats().keyframes, 20);
  EXPECT_EQ(corrector.stats().wall_headings, 0);
}

TEST(PoseCorrector, EveryObservationBelongsToTheKeyframeThatFinalisesIt) {
  const TrueMap map(room());
  PoseCorrector corrector;
  std::vector<uint64_t> ids;
  for (int i = 0; i < 40; ++i) {
    auto id = corrector.add("r1", i * 100'000'000LL, Pose{1.0 + 0.03 * i, 1.0, 0.0}, true, {});
    ASSERT_TRUE(id);
    ids.push_back(*id);
  }
  std::vector<KeyframeCorrection> finalised;
  corrector.process(map.view(), 40 * 100'000'000LL + 10'000'000'000LL, finalised);  // long silence
  ASSERT_FALSE(finalised.empty());
  for (uint64_t id : ids) {
    EXPECT_TRUE(std::any_of(finalised.begin(), finalised.end(), [&](const auto& k) { return k.id == id; }))
        << "keyframe " << id << " never finalised";
  }
}

TEST(PoseCorrector, BadInputIsRejectedAndChangesNothing) {
  PoseCorrector corrector;
  const std::vector<Vec2> bad{{std::nan(""), 1.0}};
  EXPECT_FALSE(corrector.add("r1", 0, {}, true, bad));
  EXPECT_FALSE(corrector.add("r1", 0, {std::numeric_limits<double>::infinity(), 0, 0}, true, {}));
  EXPECT_FALSE(corrector.set_initial_pose("ghost", {1, 2, 0}));
  ASSERT_TRUE(corrector.add("r1", 0, {1, 1, 0}, true, {}));
  EXPECT_FALSE(corrector.set_initial_pose("r1", {std::nan(""), 2, 0}));
  EXPECT_EQ(corrector.correction("r1"), Pose{});
  EXPECT_EQ(corrector.stats().rejected_inputs, 4);
}

TEST(PoseCorrector, InitialPosePlacesTheRobotWhereTheOperatorSays) {
  PoseCorrector corrector;
  ASSERT_TRUE(corrector.add("with_heading", 0, {1, 0, 0.5}, true, {}));
  ASSERT_TRUE(corrector.set_initial_pose("with_heading", {3, 4, 1.0}));
  const Pose placed = corrector.correction("with_heading").compose(Pose{1, 0, 0.5});
  EXPECT_NEAR(placed.x, 3, 1e-9);
  EXPECT_NEAR(placed.y, 4, 1e-9);
  EXPECT_NEAR(placed.theta, 1.0, 1e-9);

  // v1: no heading; theta is the rotation of the odometry frame.
  ASSERT_TRUE(corrector.add("v1", 0, {1, 0, 0}, false, {}));
  ASSERT_TRUE(corrector.set_initial_pose("v1", {3, 4, std::numbers::pi / 2}));
  const Pose c = corrector.correction("v1");
  const Vec2 p = c.transform({1, 0});
  EXPECT_NEAR(p.x, 3, 1e-9);
  EXPECT_NEAR(p.y, 4, 1e-9);
  EXPECT_NEAR(c.theta, std::numbers::pi / 2, 1e-9);
  std::vector<RobotCorrection> changed;
  corrector.take_changed(changed);
  ASSERT_EQ(changed.size(), 2u);
  EXPECT_EQ(changed[1].source, CorrectionSource::Operator);
  EXPECT_GT(changed[1].version, 0u);
}

TEST(PoseCorrector, AnOdometryJumpStartsANewSegmentInsteadOfAMotion) {
  const TrueMap map(room());
  PoseCorrector corrector;
  std::vector<KeyframeCorrection> finalised;
  ASSERT_TRUE(corrector.add("r1", 0, {1, 1, 0}, true, {}));
  ASSERT_TRUE(corrector.add("r1", 100'000'000, {30, 30, 0}, true, {}));  // reset / teleport
  corrector.process(map.view(), 10'000'000'000LL, finalised);
  EXPECT_EQ(corrector.stats().segments, 1);
  ASSERT_EQ(finalised.size(), 2u);
  EXPECT_EQ(finalised[0].segment, 0u);
  EXPECT_EQ(finalised[1].segment, 1u);
}

TEST(PoseCorrector, RestoredKeyframesGiveBackEachRobotsLatestCorrection) {
  PoseCorrector corrector;
  const std::vector<KeyframeCorrection> stored{{1, "a", 0, {0, 0, 0}, {0.1, 0, 0}},
                                               {2, "a", 0, {1, 0, 0}, {0.2, 0.1, 0.01}},
                                               {3, "b", 0, {0, 0, 0}, {-0.3, 0, 0}}};
  corrector.restore(stored);
  EXPECT_EQ(corrector.correction("a"), (Pose{0.2, 0.1, 0.01}));
  EXPECT_EQ(corrector.correction("b"), (Pose{-0.3, 0, 0}));
  std::vector<RobotCorrection> changed;
  corrector.take_changed(changed);
  ASSERT_EQ(changed.size(), 2u);
  EXPECT_EQ(changed[0].source, CorrectionSource::Restored);
  // New keyframes continue after the stored ids.
  auto id = corrector.add("a", 0, {1, 0, 0}, true, {});
  ASSERT_TRUE(id);
  EXPECT_EQ(*id, 4u);
}

}  // namespace
}  // namespace slam::correction
