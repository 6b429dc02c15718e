// The replay loop (eval/replay.hpp): the same recorded observations give the same corrections every
// time, whatever the machine's timing, and a robot with exact odometry stays where the truth says.
#include "eval/replay.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "synthetic_world.hpp"
#include "temp_dir.hpp"

namespace slam::bench {
namespace {

// A robot with exact odometry drives four laps of a rectangle in an 8 x 6 m room with two inner
// walls, 0.05 m per message at 10 Hz, seeing 10 beams per message (1 cm of range noise); a truth
// sample every second. From the third lap on it is tied to the first (older than 60 s), and the
// ties of the fourth start a graph optimisation, whose timing must not change the corrections
// (with three laps the ties were too few once the matches were refined against the points: their
// closure moved nothing, and no optimisation ran). The walls lie on the centres of the mapper's 5 cm cells:
// on cell edges, the map's walls land half a cell off (a ray clears the near cell) and every match is biased
// by it, 2.5 cm RMSE here with exact odometry (docs/mapping-quality.md, "drift 0").
struct Recording {
  std::vector<mapper::OwnedObservation> observations;
  std::vector<TruthSample> truth;
};

Recording drive() {
  testkit::SyntheticWorld world;
  constexpr double kCentre = 0.025;  // the default grid's cells span [k * 0.05, (k + 1) * 0.05)
  world.room({kCentre, kCentre}, {8.0 + kCentre, 6.0 + kCentre});
  world.wall({3.0 + kCentre, kCentre}, {3.0 + kCentre, 2.5});
  world.wall({5.5 + kCentre, 6.0 + kCentre}, {5.5 + kCentre, 3.5});
  testkit::SparseSensor sensor;
  sensor.noise_m = 0.01;
  std::mt19937 rng(3);
  const std::vector<Vec2> corners{{1.5, 1.5}, {6.5, 1.5}, {6.5, 4.5}, {1.5, 4.5}};
  Recording r;
  Pose pose{1.5, 1.5, 0.0};
  int64_t stamp = 1'700'000'000'000'000'000;
  uint64_t seq = 0;
  std::vector<Vec2> hits;
  for (int lap = 0; lap < 4; ++lap) {
    for (size_t c = 0; c < corners.size(); ++c) {
      const Vec2 target = corners[(c + 1) % corners.size()];
      while (distance(pose.position(), target) > 0.01) {
        const Vec2 to = target - pose.position();
        const double step = std::min(0.05, norm(to));
        pose = Pose{pose.x, pose.y, std::atan2(to.y, to.x)}.compose(Pose{step, 0.0, 0.0});
        stamp += 100'000'000;
        hits.clear();
        sensor.observe(world, pose, Pose{}, rng, hits);  // the odometry frame is the world's
        r.observations.emplace_back().assign("r1", ++seq, stamp,
                                             {pose.x, pose.y, pose.theta, true, hits, {}});
        if (seq % 10 == 0) r.truth.push_back({stamp, {"r1", pose, pose}});
      }
    }
  }
  return r;
}

TEST(Replay, TheSameRecordingGivesTheSameCorrectionsAndExactOdometryStaysExact) {
  const Recording recording = drive();
  testkit::TempDir dir("replay-test");
  RunRecorder first(0, 0.2), second(0, 0.2);
  auto a = replay(recording.observations, recording.truth, {}, first, dir.path() / "a.yaml");
  ASSERT_TRUE(a) << a.message();
  auto b = replay(recording.observations, recording.truth, {}, second, dir.path() / "b.yaml");
  ASSERT_TRUE(b) << b.message();
  EXPECT_GT(a->stats.matched, 50);
  EXPECT_GT(a->stats.optimisations, 0);
  const auto samples = first.samples();
  const auto again = second.samples();
  ASSERT_EQ(samples.size(), recording.truth.size());
  ASSERT_EQ(again.size(), samples.size());
  for (size_t i = 0; i < samples.size(); ++i) {
    EXPECT_EQ(samples[i].corrected, again[i].corrected) << "sample " << i;
  }
  const TrajectoryErrors ate = trajectory_errors(samples, false);
  RecordProperty("ate_rmse_mm", static_cast<int>(ate.corrected.rmse * 1000));
  RecordProperty("ate_max_mm", static_cast<int>(ate.corrected.max * 1000));
  EXPECT_LT(ate.corrected.rmse, 0.01);
  EXPECT_LT(ate.corrected.max, 0.03);
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "a.pgm"));
}

TEST(Replay, AMissingOrEmptyRecordingIsAnError) {
  testkit::TempDir dir("replay-test");
  auto missing = read_observations(dir.path() / "none.db");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.message().find("no recording"), std::string::npos);
  RunRecorder recorder(0, 0.2);
  auto nothing = replay({}, {}, {}, recorder, dir.path() / "map.yaml");
  ASSERT_FALSE(nothing);
  EXPECT_EQ(nothing.message(), "nothing to replay: no observation");
}

}  // namespace
}  // namespace slam::bench
