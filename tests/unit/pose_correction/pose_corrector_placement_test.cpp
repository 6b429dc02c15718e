// Global localisation (CorrectorOptions::global_localisation): a laser robot switched on anywhere in
// a mapped room, or together with the first robot, is found before any of its keyframes is
// finalised; in one of two identical rooms it is never placed, not even by its odometry once it has
// fallen silent.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "pose_correction/pose_corrector.hpp"
#include "room_scene.hpp"

namespace slam::correction {
namespace {

using testing_scene::laser_hits;
using testing_scene::room;
using testing_scene::Wall;
using testkit::centred_geometry;
using TrueMap = testing_scene::WallMap;

struct Placed {
  double error_m = 0.0;            // the second robot's corrected pose against the truth at the end
  double worst_finalised_m = 0.0;  // its finalised keyframes against the truth where they were made
  CorrectorStats stats;
  Placement placement = Placement::Unplaced;
  int drawn_after_silence = 0;  // its keyframes finalised (not dropped) once it fell silent for long
};

// A first robot maps the room at its true pose; a second, with a laser (180 beams, 8 m), is switched
// on at `start` with its odometry at (0, 0, 0) and drives a slow arc.
Placed switch_on_anywhere(const std::vector<Wall>& walls, const TrueMap& map, const Pose& start,
                          int lead_messages = 30) {
  CorrectorOptions options;
  options.global_localisation = true;
  PoseCorrector corrector(options);
  std::vector<KeyframeCorrection> finalised;
  int64_t stamp = 0;
  const auto scan = [&](const Pose& truth, const Pose& belief) { return laser_hits(walls, truth, belief); };
  for (int i = 0; i < lead_messages; ++i) {  // the first robot, along the room where it truly is
    const Pose truth{1.5 + 0.03 * i, 1.0, 0.0};
    stamp += 100'000'000;
    EXPECT_TRUE(corrector.add("first", stamp, truth, true, scan(truth, truth)));
    corrector.process(map.view(), stamp, finalised);
  }
  std::vector<std::pair<uint64_t, Pose>> truth_at;  // keyframe id -> the second robot's truth
  Pose truth = start, belief;
  for (int i = 0; i < 40; ++i) {
    const Pose step{0.03, 0.0, 0.01};
    truth = truth.compose(step);
    belief = belief.compose(step);
    stamp += 100'000'000;
    const auto id = corrector.add("second", stamp, belief, true, scan(truth, belief));
    EXPECT_TRUE(id);
    if (id) truth_at.emplace_back(*id, truth.compose(belief.inverse()));  // map_from_odom's truth
    corrector.process(map.view(), stamp, finalised);
  }
  Placed out;
  for (const KeyframeCorrection& k : finalised) {
    if (k.robot != "second") continue;
    for (const auto& [id, frame] : truth_at)
      if (id == k.id)
        out.worst_finalised_m =
            std::max(out.worst_finalised_m,
                     distance(k.correction.compose(k.odom).position(), frame.compose(k.odom).position()));
  }
  out.error_m = distance(corrector.correction("second").compose(belief).position(), truth.position());
  out.stats = corrector.stats();
  std::vector<RobotCorrection> changed;
  corrector.take_changed(changed);
  for (const RobotCorrection& c : changed)
    if (c.robot == "second") out.placement = c.placement;
  // Silent from now on, for a minute: a robot not found is still not drawn where its odometry says.
  const size_t before_silence = finalised.size();
  corrector.process(map.view(), stamp + 60'000'000'000LL, finalised);
  for (size_t i = before_silence; i < finalised.size(); ++i)
    out.drawn_after_silence += finalised[i].robot == "second" && !finalised[i].discarded ? 1 : 0;
  return out;
}

TEST(PoseCorrector, ARobotSwitchedOnAnywhereIsFoundOnTheMapBeforeItDrawsAnything) {
  const TrueMap map(room(), centred_geometry({-0.5, -0.5}, {6.5, 5.5}));
  for (const Pose start : {Pose{4.6, 3.0, 2.0}, Pose{1.0, 3.2, -1.2}, Pose{3.0, 1.0, 3.0}}) {
    SCOPED_TRACE(testing::Message() << "start " << start.x << ", " << start.y << ", " << start.theta);
    const Placed p = switch_on_anywhere(room(), map, start);
    EXPECT_EQ(p.stats.robots_placed, 1);
    EXPECT_EQ(p.placement, Placement::Placed);
    EXPECT_LT(p.error_m, 0.05);
    EXPECT_LT(p.worst_finalised_m, 0.05);  // none of its keyframes was finalised where it is not
  }
}

TEST(PoseCorrector, ARobotSwitchedOnWithTheFirstIsSearchedForToo) {
  // The first robot has sent one message, no keyframe yet: the second is still not taken to start
  // where its odometry says (stacked on the first's origin).
  const TrueMap map(room(), centred_geometry({-0.5, -0.5}, {6.5, 5.5}));
  const Placed p = switch_on_anywhere(room(), map, {4.6, 3.0, 2.0}, 1);
  EXPECT_EQ(p.stats.robots_placed, 1);
  EXPECT_LT(p.error_m, 0.05);
}

TEST(PoseCorrector, ARobotInOneOfTwoIdenticalRoomsIsNotPlacedInEither) {
  std::vector<Wall> twins = room();
  for (const Wall& w : room()) twins.push_back({w.a + Vec2{8.0, 0.0}, w.b + Vec2{8.0, 0.0}});
  const TrueMap map(twins, centred_geometry({-0.5, -0.5}, {14.5, 5.5}));
  const Placed p = switch_on_anywhere(twins, map, {12.6, 3.0, 2.0});
  EXPECT_EQ(p.stats.robots_placed, 0);
  // Its 1.2 m of driving searched each half metre (CorrectorOptions::placement_search_travel_m),
  // not at each of its dozen keyframes; none placed.
  EXPECT_GE(p.stats.placement_searches, 2);
  EXPECT_LE(p.stats.placement_searches, 3);
  EXPECT_NE(p.placement, Placement::Placed);
  EXPECT_EQ(p.drawn_after_silence, 0);
}

struct Carried {
  double error_m = 0.0;    // its corrected pose against the truth at the end
  int drawn_wrong = 0;     // finalised keyframes drawn more than 0.2 m from where they were made
  int discarded = 0;       // keyframes dropped while it was searched for
  bool seen_lost = false;  // its correction was published as lost
  Placement placement = Placement::Lost;
  CorrectorStats stats;
};

// A laser robot maps along the first room of `walls`, is carried to `to` (its odometry goes on as
// if nothing happened) and drives a slow arc there for `messages` messages.
Carried carry(const CorrectorOptions& options, const std::vector<Wall>& walls, const TrueMap& map,
              const Pose& to, int messages = 60) {
  PoseCorrector corrector(options);
  std::vector<KeyframeCorrection> finalised;
  std::vector<RobotCorrection> changed;
  std::vector<std::pair<uint64_t, Pose>> truth_at;  // keyframe id -> map_from_odom's truth
  Carried out;
  int64_t stamp = 0;
  Pose truth{1.5, 1.0, 0.0}, odometry = truth;
  auto send = [&](const Pose& step) {
    truth = truth.compose(step);
    odometry = odometry.compose(step);
    stamp += 100'000'000;
    const auto id = corrector.add("r1", stamp, odometry, true, laser_hits(walls, truth, odometry));
    ASSERT_TRUE(id);
    truth_at.emplace_back(*id, truth.compose(odometry.inverse()));
    corrector.process(map.view(), stamp, finalised);
    corrector.take_changed(changed);
    for (const RobotCorrection& c : changed) {
      out.seen_lost = out.seen_lost || c.placement == Placement::Lost;
      out.placement = c.placement;
    }
    changed.clear();
  };
  for (int i = 0; i < 30; ++i) send({0.03, 0.0, 0.0});
  truth = to;
  for (int i = 0; i < messages; ++i) send({0.03, 0.0, 0.01});
  for (const KeyframeCorrection& k : finalised) {
    if (k.discarded) {
      ++out.discarded;
      continue;
    }
    for (const auto& [id, frame] : truth_at)
      if (id == k.id &&
          distance(k.correction.compose(k.odom).position(), frame.compose(k.odom).position()) > 0.2)
        ++out.drawn_wrong;
  }
  out.error_m = distance(corrector.correction("r1").compose(odometry).position(), truth.position());
  out.stats = corrector.stats();
  return out;
}

TEST(PoseCorrector, ACarriedRobotIsLostThenFoundAgainWithoutDrawingWhereItIsNot) {
  const TrueMap map(room(), centred_geometry({-0.5, -0.5}, {6.5, 5.5}));
  CorrectorOptions never_lost;
  never_lost.lost_after_unmatched = 0;
  for (const Pose to : {Pose{4.6, 3.0, 2.0}, Pose{1.0, 3.2, -1.2}}) {
    SCOPED_TRACE(testing::Message() << "carried to " << to.x << ", " << to.y << ", " << to.theta);
    const Carried c = carry(CorrectorOptions{}, room(), map, to);
    EXPECT_EQ(c.stats.robots_lost, 1);
    EXPECT_TRUE(c.seen_lost);
    EXPECT_EQ(c.stats.robots_placed, 1);
    EXPECT_EQ(c.placement, Placement::Placed);
    EXPECT_LT(c.error_m, 0.05);
    EXPECT_EQ(c.discarded, 0);
    // Unaware, it draws every keyframe after the carry where it is not (60 messages, about 50
    // keyframes); aware, only those until its scores told (in this small room a wrong place
    // still scores 0.6-0.75, so that takes a while).
    const Carried unaware = carry(never_lost, room(), map, to);
    EXPECT_EQ(unaware.stats.robots_lost, 0);
    EXPECT_GT(unaware.error_m, 0.5);
    EXPECT_LT(c.drawn_wrong, unaware.drawn_wrong / 2);
  }
}

TEST(PoseCorrector, LocalisingOnlyACarriedRobotIsLostThenFoundAgain) {
  // On a fixed map nothing it sees is drawn, so after the carry nothing of its own fits its
  // prediction either: it is found lost and placed again, its carried keyframes never published
  // where it is not.
  const TrueMap map(room(), centred_geometry({-0.5, -0.5}, {6.5, 5.5}));
  CorrectorOptions options;
  options.localise_only = true;
  const Carried c = carry(options, room(), map, {4.6, 3.0, 2.0});
  EXPECT_EQ(c.stats.robots_lost, 1);
  EXPECT_TRUE(c.seen_lost);
  EXPECT_EQ(c.stats.robots_placed, 2);  // switched on, then after the carry
  EXPECT_EQ(c.placement, Placement::Placed);
  EXPECT_LT(c.error_m, 0.05);
}

TEST(PoseCorrector, ALostRobotThatFindsNothingKeepsOnlyItsLatestKeyframes) {
  // Carried into the second of two identical rooms: it is never placed (not by its odometry
  // either), and its older keyframes are dropped.
  std::vector<Wall> twins = room();
  for (const Wall& w : room()) twins.push_back({w.a + Vec2{8.0, 0.0}, w.b + Vec2{8.0, 0.0}});
  const TrueMap map(twins, centred_geometry({-0.5, -0.5}, {14.5, 5.5}));
  CorrectorOptions options;
  options.placement_max_keyframes = 5;
  const Carried c = carry(options, twins, map, {12.6, 3.0, 2.0}, 120);
  EXPECT_EQ(c.stats.robots_lost, 1);
  EXPECT_EQ(c.stats.robots_placed, 0);
  EXPECT_EQ(c.placement, Placement::Lost);
  EXPECT_GT(c.discarded, 0);
  EXPECT_EQ(c.stats.unplaced_keyframes_dropped, c.discarded);
}

}  // namespace
}  // namespace slam::correction

namespace slam::correction {
namespace {

// A laser robot switched on at `start` with its odometry at (0, 0, 0), driving a slow arc in `walls`
// while the corrector searches for it on `map`: what an operator's answers are tried on.
class SwitchedOn {
 public:
  SwitchedOn(const CorrectorOptions& options, std::vector<Wall> walls, const TrueMap& map, const Pose& start)
      : corrector(options), walls_(std::move(walls)), map_(map), truth_(start) {}

  void drive(int messages) {
    for (int i = 0; i < messages; ++i) {
      const Pose step{0.03, 0.0, 0.01};
      truth_ = truth_.compose(step);
      odometry_ = odometry_.compose(step);
      stamp_ += 100'000'000;
      EXPECT_TRUE(corrector.add("r1", stamp_, odometry_, true, laser_hits(walls_, truth_, odometry_)));
      corrector.process(map_.view(), stamp_, finalised_);
    }
  }
  // The latest published placement state.
  Placement placement() {
    corrector.take_changed(changed_);
    if (!changed_.empty()) placement_ = changed_.back().placement;
    changed_.clear();
    return placement_;
  }
  double error_m() const {
    return distance(corrector.correction("r1").compose(odometry_).position(), truth_.position());
  }

  PoseCorrector corrector;

 private:
  std::vector<Wall> walls_;
  const TrueMap& map_;
  Pose truth_, odometry_;
  int64_t stamp_ = 0;
  std::vector<KeyframeCorrection> finalised_;
  std::vector<RobotCorrection> changed_;
  Placement placement_ = Placement::Unplaced;
};

CorrectorOptions searching(int confirmations) {
  CorrectorOptions o;
  o.localise_only = true;
  o.placement_confirmations = confirmations;
  return o;
}

TEST(PoseCorrector, AnOperatorAcceptsAPlacementBeingConfirmed) {
  const TrueMap map(room(), centred_geometry({-0.5, -0.5}, {6.5, 5.5}));
  SwitchedOn robot(searching(1000), room(), map, {4.6, 3.0, 2.0});  // never confirmed by itself
  EXPECT_FALSE(robot.corrector.answer_placement("r1", true)) << "unknown robot";
  robot.drive(20);
  ASSERT_EQ(robot.placement(), Placement::Placing);
  ASSERT_TRUE(robot.corrector.answer_placement("r1", true));
  EXPECT_EQ(robot.placement(), Placement::Placed);
  robot.drive(10);
  EXPECT_LT(robot.error_m(), 0.05);
  const Status again = robot.corrector.answer_placement("r1", true);
  EXPECT_FALSE(again);
  EXPECT_NE(again.message().find("placed already"), std::string::npos) << again.message();
}

TEST(PoseCorrector, APlaceAnOperatorRejectedIsNeverTakenAgain) {
  // The map holds one room; the robot is truly in its twin, 8 m off the map: the search finds the
  // mapped room, an operator says no, and the robot stays searched for, never placed there.
  std::vector<Wall> twin;
  for (const Wall& w : room()) twin.push_back({w.a + Vec2{8.0, 0.0}, w.b + Vec2{8.0, 0.0}});
  const TrueMap map(room(), centred_geometry({-0.5, -0.5}, {6.5, 5.5}));
  SwitchedOn robot(searching(3), twin, map, {12.6, 3.0, 2.0});
  robot.drive(1);
  EXPECT_FALSE(robot.corrector.answer_placement("r1", false)) << "nothing found yet: nothing to reject";
  for (int i = 0; i < 40 && robot.placement() != Placement::Placing; ++i) robot.drive(1);
  ASSERT_EQ(robot.placement(), Placement::Placing);
  ASSERT_TRUE(robot.corrector.answer_placement("r1", false));
  EXPECT_EQ(robot.placement(), Placement::Unplaced);
  robot.drive(60);
  EXPECT_NE(robot.placement(), Placement::Placed);
  EXPECT_EQ(robot.corrector.stats().robots_placed, 0);
  EXPECT_GT(robot.corrector.stats().placements_refused, 0);
}

TEST(PoseCorrector, AnOperatorRejectingAPlacedRobotHasItSearchedForAgain) {
  std::vector<Wall> twin;
  for (const Wall& w : room()) twin.push_back({w.a + Vec2{8.0, 0.0}, w.b + Vec2{8.0, 0.0}});
  const TrueMap map(room(), centred_geometry({-0.5, -0.5}, {6.5, 5.5}));
  SwitchedOn robot(searching(3), twin, map, {12.6, 3.0, 2.0});
  robot.drive(30);
  ASSERT_EQ(robot.placement(), Placement::Placed);  // wrongly, in the mapped room
  ASSERT_TRUE(robot.corrector.answer_placement("r1", false));
  EXPECT_EQ(robot.placement(), Placement::Lost);
  robot.drive(60);
  EXPECT_EQ(robot.placement(), Placement::Lost);  // the same room is found, and refused
  EXPECT_EQ(robot.corrector.stats().robots_placed, 1);
  // An operator's pose ends it: the robot is where the operator says.
  ASSERT_TRUE(robot.corrector.set_initial_pose("r1", Pose{1.0, 1.0, 0.0}));
  EXPECT_EQ(robot.placement(), Placement::Placed);
}

TEST(PoseCorrector, ARobotStandingWhereNothingIsMappedYetIsFoundOnceTheMapReachesIt) {
  // Switched on where the map does not reach yet, it stands still. The others map on; once the map
  // holds its room it is found where it stands, without having to move.
  CorrectorOptions options;
  options.global_localisation = true;
  PoseCorrector corrector(options);
  corrector.set_map_given(true);
  const GridGeometry geometry = centred_geometry({-0.5, -0.5}, {20.5, 5.5});
  const TrueMap elsewhere({{{10.0, 0.0}, {20.0, 0.0}}, {{10.0, 1.2}, {20.0, 1.2}}}, geometry);
  const TrueMap mapped(room(), geometry);
  const Pose truth{3.0, 1.0, 3.0};
  std::vector<KeyframeCorrection> finalised;
  int64_t stamp = 0;
  for (int i = 0; i < 300; ++i) {  // 30 s at 10 Hz, the map reaching it after 12 s
    stamp += 100'000'000;
    ASSERT_TRUE(corrector.add("standing", stamp, Pose{}, true, laser_hits(room(), truth, Pose{})));
    corrector.process(i < 120 ? elsewhere.view() : mapped.view(), stamp, finalised);
    if (i == 119) {
      EXPECT_EQ(corrector.stats().robots_placed, 0);
    }
  }
  EXPECT_EQ(corrector.stats().robots_placed, 1);
  EXPECT_LT(distance(corrector.correction("standing").position(), truth.position()), 0.05);
}

TEST(PoseCorrector, ARobotAmongLookAlikesIsSearchedForLessOftenTheLongerItDrives) {
  // In the second of two identical rooms every whole-map search finds two places: the travel before
  // the next search doubles (0.5, 1, 2, 4 m), so 6 m of driving cost a handful of searches, not twelve.
  std::vector<Wall> twins = room();
  for (const Wall& w : room()) twins.push_back({w.a + Vec2{8.0, 0.0}, w.b + Vec2{8.0, 0.0}});
  const TrueMap map(twins, centred_geometry({-0.5, -0.5}, {14.5, 5.5}));
  CorrectorOptions options;
  options.global_localisation = true;
  PoseCorrector corrector(options);
  corrector.set_map_given(true);
  std::vector<KeyframeCorrection> finalised;
  Pose truth{11.0, 2.5, 0.0}, belief;
  int64_t stamp = 0;
  for (int i = 0; i < 300; ++i) {  // a circle of 1 m radius, 6 m in 30 s
    const Pose step{0.02, 0.0, 0.02};
    truth = truth.compose(step);
    belief = belief.compose(step);
    stamp += 100'000'000;
    ASSERT_TRUE(corrector.add("twin", stamp, belief, true, laser_hits(twins, truth, belief)));
    corrector.process(map.view(), stamp, finalised);
  }
  EXPECT_EQ(corrector.stats().robots_placed, 0);
  EXPECT_GE(corrector.stats().placement_searches, 3);
  EXPECT_LE(corrector.stats().placement_searches, 6);
}

TEST(PoseCorrector, RobotsRestoredFromTheStoreStayPlaced) {
  // Keyframes are stored only once a robot is placed: after a restart each robot is where the
  // store says, not searched for again (the second one restored would otherwise join a map that
  // exists and count as unplaced).
  CorrectorOptions options;
  options.global_localisation = true;
  PoseCorrector corrector(options);
  const std::vector<KeyframeCorrection> stored{{1, "a", 0, {0, 0, 0}, {0.1, 0, 0}},
                                               {2, "b", 0, {0, 0, 0}, {3.0, -1.0, 1.2}}};
  corrector.restore(stored);
  std::vector<RobotCorrection> changed;
  corrector.take_changed(changed);
  ASSERT_EQ(changed.size(), 2u);
  for (const RobotCorrection& c : changed) {
    EXPECT_EQ(c.placement, Placement::Placed) << c.robot;
    EXPECT_EQ(c.source, CorrectionSource::Restored) << c.robot;
  }
  EXPECT_EQ(corrector.correction("b"), (Pose{3.0, -1.0, 1.2}));
  // A robot the store does not know joins a map that exists: its keyframe waits to be placed.
  ASSERT_TRUE(corrector.add("c", 0, {0, 0, 0}, true, {}));
  const TrueMap map(room());
  std::vector<KeyframeCorrection> finalised;
  corrector.process(map.view(), 10'000'000'000LL, finalised);  // its keyframe closes (silent)
  EXPECT_TRUE(finalised.empty());
  EXPECT_EQ(corrector.stats().robots_placed, 0);
}

}  // namespace
}  // namespace slam::correction
