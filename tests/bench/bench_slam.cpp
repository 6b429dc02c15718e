// bench_slam: speed of the SLAM core. Keyframe matching: a 100-point keyframe (ten v1 messages of
// ten points) against an office-sized 0.05 m grid (400 x 400 cells) in the tracking window
// (+-0.15 m, +-0.08 rad). Target: 500 robots x 10 Hz with keyframes of ten messages is 500 matches/s
// on one core, i.e. <= 2 ms per match. A loop-closure-sized window is measured for reference, as are
// the two steps done with every match: the reading of the keyframe's wall directions (the walls'
// heading) and the refinement against the points of the keyframes around it. The branch-and-bound
// search (global localisation, wide loop closures) is measured over the whole office at every
// heading and over a +-3 m, +-0.6 rad closure region, with laser keyframes (360 beams, 8 m).
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "pose_correction/branch_and_bound_search.hpp"
#include "pose_correction/gaussian_pose.hpp"
#include "pose_correction/point_refiner.hpp"
#include "pose_correction/scan_matcher.hpp"
#include "pose_correction/wall_axes.hpp"
#include "synthetic_world.hpp"

namespace {

using slam::Pose;
using slam::Vec2;
using slam::correction::ScanMatcher;
using slam::correction::SearchWindow;
using slam::testkit::ClassGrid;
using slam::testkit::SparseSensor;
using slam::testkit::SyntheticWorld;

constexpr int kPointsPerKeyframe = 100;
constexpr int kKeyframes = 32;

// 20 x 20 m: four by four offices of 5 x 5 m with doorways, a desk in each for asymmetry.
SyntheticWorld office() {
  SyntheticWorld w;
  w.room({0.0, 0.0}, {20.0, 20.0});
  for (int i = 1; i < 4; ++i) {
    const double c = 5.0 * i;
    for (int j = 0; j < 4; ++j) {
      const double lo = 5.0 * j, hi = lo + 5.0;
      w.wall({c, lo}, {c, lo + 2.0});  // doorway from lo + 2 to lo + 3
      w.wall({c, lo + 3.0}, {c, hi});
      w.wall({lo, c}, {lo + 1.0, c});  // doorway from lo + 1 to lo + 2
      w.wall({lo + 2.0, c}, {hi, c});
    }
  }
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) w.room({5.0 * i + 3.0, 5.0 * j + 3.5}, {5.0 * i + 4.2, 5.0 * j + 4.2});
  return w;
}

struct Keyframe {
  std::vector<Vec2> points;
  Pose predicted;
  Pose truth;
  // The points of the keyframes around it (map frame), as the corrector gathers them to refine the
  // match: 60 keyframes of 100 points from poses within 2 m.
  std::vector<Vec2> around;
};
constexpr int kKeyframesAround = 60;

struct Scene {
  ClassGrid grid;
  std::vector<Keyframe> keyframes;
};

// Keyframes in random offices, each from ten ten-beam messages while driving 0.5 m, predicted
// with an error inside the tracking window.
const Scene& scene() {
  static const Scene s = [] {
    const SyntheticWorld world = office();
    slam::GridGeometry geometry;
    geometry.resolution = 0.05;
    geometry.width = 400;
    geometry.height = 400;
    Scene out{ClassGrid::rasterise(world, geometry), {}};
    std::mt19937 rng(42), around_rng(7);
    std::uniform_int_distribution<int> office_index(0, 3);
    std::uniform_real_distribution<double> inside(1.0, 2.5), heading(-3.1, 3.1), error(-1.0, 1.0);
    SparseSensor sensor;
    sensor.noise_m = 0.01;
    sensor.max_range_m = 8.0;
    while (static_cast<int>(out.keyframes.size()) < kKeyframes) {
      const Pose start{5.0 * office_index(rng) + inside(rng), 5.0 * office_index(rng) + inside(rng),
                       heading(rng)};
      Keyframe k;
      Pose pose = start;
      for (int message = 0; message < 10; ++message) {
        sensor.observe(world, pose, start, rng, k.points);
        pose = pose.compose({0.05, 0.0, 0.02});
      }
      if (static_cast<int>(k.points.size()) < kPointsPerKeyframe) continue;  // beams lost through doorways
      k.points.resize(kPointsPerKeyframe);
      k.predicted = {start.x + 0.1 * error(rng), start.y + 0.1 * error(rng), start.theta + 0.05 * error(rng)};
      k.truth = start;
      for (int around = 0; around < kKeyframesAround; ++around) {
        // A generator of its own, so the keyframes stay those the match benches have always used.
        const Pose from{start.x + 2.0 * error(around_rng), start.y + 2.0 * error(around_rng),
                        heading(around_rng)};
        std::vector<Vec2> points;
        for (int message = 0; message < 10; ++message)
          sensor.observe(world, from, Pose{}, around_rng, points);
        if (points.size() > kPointsPerKeyframe) points.resize(kPointsPerKeyframe);
        k.around.insert(k.around.end(), points.begin(), points.end());
      }
      out.keyframes.push_back(std::move(k));
    }
    return out;
  }();
  return s;
}

void run_matches(benchmark::State& state, const SearchWindow& window) {
  const Scene& s = scene();
  const slam::correction::GridView view{s.grid.geometry, s.grid.classes};
  ScanMatcher matcher;
  size_t next = 0;
  int64_t failed = 0;
  for (auto _ : state) {
    const Keyframe& k = s.keyframes[next];
    next = (next + 1) % s.keyframes.size();
    const auto r = matcher.match(view, k.points, k.predicted, window);
    if (!r) ++failed;
    benchmark::DoNotOptimize(r);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["failed"] = static_cast<double>(failed);
  if (failed > 0) state.SkipWithError("some keyframes did not match");
}

void BM_KeyframeMatch(benchmark::State& state) {
  run_matches(state, {0.15, 0.08});
}
BENCHMARK(BM_KeyframeMatch)->Unit(benchmark::kMicrosecond);

// A loop closure searches wider: +-1 m, +-0.3 rad.
void BM_LoopClosureMatch(benchmark::State& state) {
  run_matches(state, {1.0, 0.3});
}
BENCHMARK(BM_LoopClosureMatch)->Unit(benchmark::kMillisecond);

// The walls' directions of each keyframe (WallAxisReader), as the corrector reads them after the
// tracking match.
void BM_WallAxisReading(benchmark::State& state) {
  const Scene& s = scene();
  slam::correction::WallAxisReader reader;
  const slam::correction::WallAxisOptions options;
  size_t next = 0;
  int64_t read = 0;
  for (auto _ : state) {
    const auto reading = reader.read(s.keyframes[next].points, options);
    next = (next + 1) % s.keyframes.size();
    read += reading ? 1 : 0;
    benchmark::DoNotOptimize(reading);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["read_share"] = static_cast<double>(read) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_WallAxisReading)->Unit(benchmark::kMicrosecond);

// The refinement of a match against the points of the keyframes around it (PointRefiner), started
// where a grid search leaves it (half a cell and half a heading step off), binning included.
void BM_PointRefinement(benchmark::State& state) {
  const Scene& s = scene();
  slam::correction::PointRefiner refiner;
  const auto prior = slam::correction::diagonal(0.03, 0.03, 0.01);
  size_t next = 0;
  int64_t refined = 0;
  double error_sum = 0.0;
  for (auto _ : state) {
    const Keyframe& k = s.keyframes[next];
    next = (next + 1) % s.keyframes.size();
    refiner.set_reference(k.around);
    const Pose start{k.truth.x + 0.025, k.truth.y - 0.02, k.truth.theta + 0.004};
    const auto result = refiner.refine(k.points, start, prior);
    if (result) {
      ++refined;
      error_sum += slam::distance(result->pose.position(), k.truth.position());
    }
    benchmark::DoNotOptimize(result);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["refined_share"] = static_cast<double>(refined) / static_cast<double>(state.iterations());
  // Where it left the keyframes, against 32 mm at the start.
  state.counters["error_mm"] = refined > 0 ? 1000.0 * error_sum / static_cast<double>(refined) : 0.0;
}
BENCHMARK(BM_PointRefinement)->Unit(benchmark::kMicrosecond);

// Laser keyframes (one scan of 360 beams within 8 m) at random poses in the offices.
struct LaserKeyframe {
  std::vector<Vec2> points;
  Pose truth;
};

const std::vector<LaserKeyframe>& laser_keyframes() {
  static const std::vector<LaserKeyframe> keyframes = [] {
    const SyntheticWorld world = office();
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> position(0.6, 19.4), heading(-3.1, 3.1);
    SparseSensor laser;
    laser.beams = 360;
    laser.max_range_m = 8.0;
    laser.noise_m = 0.01;
    std::vector<LaserKeyframe> out;
    while (out.size() < 16) {
      LaserKeyframe k;
      k.truth = {position(rng), position(rng), heading(rng)};
      laser.observe(world, k.truth, k.truth, rng, k.points);
      if (k.points.size() >= 200) out.push_back(std::move(k));
    }
    return out;
  }();
  return keyframes;
}

void run_branch_and_bound(benchmark::State& state, double linear_m, double angular_rad, double offset_m) {
  const Scene& s = scene();
  slam::correction::BranchAndBoundSearch search;
  if (!search.set_map({s.grid.geometry, s.grid.classes})) state.SkipWithError("map refused");
  const auto& keyframes = laser_keyframes();
  size_t next = 0;
  int64_t found = 0, nodes = 0;
  double ambiguity = 0.0;
  for (auto _ : state) {
    const LaserKeyframe& k = keyframes[next];
    next = (next + 1) % keyframes.size();
    // Global: the region is the office around its centre; a closure: around a prediction off by offset_m.
    const Pose centre = linear_m >= 10.0
                            ? Pose{10.0, 10.0, 0.0}
                            : Pose{k.truth.x + offset_m, k.truth.y - offset_m, k.truth.theta + 0.3};
    const auto m = search.search(k.points, {centre, linear_m, angular_rad});
    if (m) {
      found += slam::distance(m->pose.position(), k.truth.position()) < 0.1 ? 1 : 0;
      nodes += static_cast<int64_t>(m->nodes_scored);
      ambiguity += m->ambiguity();
    }
    benchmark::DoNotOptimize(m);
  }
  const auto n = static_cast<double>(state.iterations());
  state.SetItemsProcessed(state.iterations());
  // Offices alike down to the desk make some placements ambiguous (runner-up as good as the best).
  state.counters["found_share"] = static_cast<double>(found) / n;
  state.counters["mean_ambiguity"] = ambiguity / n;
  state.counters["nodes_per_search"] = static_cast<double>(nodes) / n;
}

void BM_GlobalSearch(benchmark::State& state) {
  run_branch_and_bound(state, 10.5, 3.2, 0.0);
}
BENCHMARK(BM_GlobalSearch)->Unit(benchmark::kMillisecond);

void BM_WideClosureSearch(benchmark::State& state) {
  run_branch_and_bound(state, 3.0, 0.6, 2.0);
}
BENCHMARK(BM_WideClosureSearch)->Unit(benchmark::kMillisecond);

// Preparing a map for the search: the likelihood field and its six max levels (400 x 400 cells).
void BM_GlobalSearchMapPreparation(benchmark::State& state) {
  const Scene& s = scene();
  slam::correction::BranchAndBoundSearch search;
  for (auto _ : state) {
    const auto status = search.set_map({s.grid.geometry, s.grid.classes});
    benchmark::DoNotOptimize(status);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_GlobalSearchMapPreparation)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
