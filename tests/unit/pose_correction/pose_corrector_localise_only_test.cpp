// Localising only on a fixed map (CorrectorOptions::localise_only), and a loaded map in a mapping
// run (PoseCorrector::set_map_given): a laser robot switched on anywhere with its odometry at
// (0, 0, 0) is searched for on the map, even as the first robot; localising only, it is then tracked
// with one pose-graph node and a pose held to the map, and one not found is never placed by its
// odometry.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>
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

struct Drive {
  double error_m = 0.0;  // its corrected pose against the truth at the end
  double sigma_m = 0.0;  // the published position sigma at the end
  Placement placement = Placement::Unplaced;
  size_t graph_keyframes = 0;
  int discarded = 0;
  CorrectorStats stats;
};

// The only robot, switched on at `start` with its odometry at (0, 0, 0), drives `messages` steps of
// a slow circle (1 m radius) on `map`, then waits silent past the placement wait.
Drive switch_on(const CorrectorOptions& options, bool map_given, const std::vector<Wall>& walls,
                const TrueMap& map, const Pose& start, int messages) {
  PoseCorrector corrector(options);
  corrector.set_map_given(map_given);
  std::vector<KeyframeCorrection> finalised;
  std::vector<RobotCorrection> changed;
  Drive out;
  Pose truth = start, odometry;
  int64_t stamp = 0;
  for (int i = 0; i < messages; ++i) {
    const Pose step{0.02, 0.0, 0.02};
    truth = truth.compose(step);
    odometry = odometry.compose({0.021, 0.001 * std::sin(i), 0.02 + 0.004 * std::cos(0.7 * i)});  // drifting
    stamp += 100'000'000;
    EXPECT_TRUE(corrector.add("r1", stamp, odometry, true, laser_hits(walls, truth, odometry)));
    corrector.process(map.view(), stamp, finalised);
    corrector.take_changed(changed);
    // On threads: a robot's messages come a tenth of a second apart, not back to back.
    if (options.match_threads > 0) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  // On threads the last searches and matches land at later passes: waits for them (a bound, not a
  // timing: a few milliseconds' work each).
  for (int i = 0; i < 500 && options.match_threads > 0 && corrector.stats().backlog + (i < 20 ? 1 : 0) > 0;
       ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    corrector.process(map.view(), stamp, finalised);
  }
  corrector.process(map.view(), stamp + 60'000'000'000LL, finalised);  // then silent for a minute
  corrector.take_changed(changed);
  for (const RobotCorrection& c : changed) {
    out.placement = c.placement;
    out.sigma_m = std::sqrt(std::max(c.covariance(0, 0), c.covariance(1, 1)));
  }
  for (const KeyframeCorrection& k : finalised) out.discarded += k.discarded ? 1 : 0;
  out.error_m = distance(corrector.correction("r1").compose(odometry).position(), truth.position());
  out.graph_keyframes = corrector.graph_keyframes();
  out.stats = corrector.stats();
  return out;
}

CorrectorOptions localise_only() {
  CorrectorOptions o;
  o.localise_only = true;
  return o;
}

TEST(PoseCorrector, LocalisingOnlyARobotIsFoundThenTrackedWithOneNodeHeldToTheMap) {
  const TrueMap map(room(), centred_geometry({-0.5, -0.5}, {6.5, 5.5}));
  for (const Pose start : {Pose{4.6, 3.0, 2.0}, Pose{1.0, 3.2, -1.2}, Pose{3.0, 1.0, 3.0}}) {
    SCOPED_TRACE(testing::Message() << "start " << start.x << ", " << start.y << ", " << start.theta);
    // 300 messages: 6 m around the circle, hundreds of keyframes.
    const Drive d = switch_on(localise_only(), false, room(), map, start, 300);
    EXPECT_EQ(d.stats.robots_placed, 1);
    EXPECT_EQ(d.placement, Placement::Placed);
    EXPECT_LT(d.error_m, 0.05);
    EXPECT_GT(d.stats.keyframes, 100);
    EXPECT_EQ(d.graph_keyframes, 1u);  // its latest keyframe only
    EXPECT_EQ(d.stats.ties_tried, 0);
    EXPECT_EQ(d.stats.optimisations, 0);
    // Each match against the fixed map holds it: no growth with the metres driven.
    EXPECT_LT(d.sigma_m, 0.03) << d.sigma_m;  // 0.09 m after these 6 m if only odometry grew it
  }
}

TEST(PoseCorrector, SearchedOnItsOwnThreadARobotIsFoundAndTrackedAsInline) {
  // The mapper's way: matching and placement searches on threads of their own, landing at later
  // passes; the search never holds up the loop.
  const TrueMap map(room(), centred_geometry({-0.5, -0.5}, {6.5, 5.5}));
  CorrectorOptions options = localise_only();
  options.match_threads = 1;
  const Drive d = switch_on(options, false, room(), map, {4.6, 3.0, 2.0}, 300);
  EXPECT_EQ(d.stats.robots_placed, 1);
  EXPECT_EQ(d.placement, Placement::Placed);
  EXPECT_LT(d.error_m, 0.05);
  EXPECT_GT(d.stats.placement_searches, 0);
}

TEST(PoseCorrector, LocalisingOnlyARobotNotFoundIsNeverPlacedByItsOdometry) {
  // In the second of two identical rooms: searched for as long as it drives, its older keyframes
  // dropped, never placed where its odometry says.
  std::vector<Wall> twins = room();
  for (const Wall& w : room()) twins.push_back({w.a + Vec2{8.0, 0.0}, w.b + Vec2{8.0, 0.0}});
  const TrueMap map(twins, centred_geometry({-0.5, -0.5}, {14.5, 5.5}));
  CorrectorOptions options = localise_only();
  options.placement_max_keyframes = 5;
  const Drive d = switch_on(options, false, twins, map, {12.6, 3.0, 2.0}, 60);
  EXPECT_EQ(d.stats.robots_placed, 0);
  EXPECT_NE(d.placement, Placement::Placed);
  EXPECT_GT(d.discarded, 0);
  EXPECT_EQ(d.stats.unplaced_keyframes_dropped, d.discarded);
}

TEST(PoseCorrector, TheFirstRobotOnALoadedMapIsSearchedFor) {
  // Mapping with global localisation: the first robot of an empty map starts where its odometry
  // says, but on a loaded map it is found where it is.
  const TrueMap map(room(), centred_geometry({-0.5, -0.5}, {6.5, 5.5}));
  CorrectorOptions options;
  options.global_localisation = true;
  const Pose start{4.6, 3.0, 2.0};
  const Drive given = switch_on(options, true, room(), map, start, 40);
  EXPECT_EQ(given.stats.robots_placed, 1);
  EXPECT_LT(given.error_m, 0.05);
  const Drive empty = switch_on(options, false, room(), map, start, 40);
  EXPECT_EQ(empty.stats.placement_searches, 0);
  EXPECT_GT(empty.error_m, 1.0);
}

}  // namespace
}  // namespace slam::correction
