// bench_slam (placement): global localisation's search on a building of 100 x 100 m mapped at
// 5 cm, as the mapper runs it (PlacementSearcher: the grid's occupied part coarsened to
// placement_whole_map_cells, a branch-and-bound search over the whole map at every heading; a
// hypothesis confirmed around it on the map coarsened to placement_max_map_cells).
// Target (issue: robots that start anywhere): one search answers within 1 s on one core.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "common/core/geometry.hpp"
#include "pose_correction/corrector_options.hpp"
#include "pose_correction/placement_search.hpp"
#include "synthetic_world.hpp"

namespace {

using slam::Pose;
using slam::Vec2;
using slam::correction::PlacementJob;
using slam::correction::PlacementSearcher;
using slam::testkit::ClassGrid;
using slam::testkit::SparseSensor;
using slam::testkit::SyntheticWorld;

constexpr double kSide_m = 100.0;
constexpr double kRoom_m = 5.0;
constexpr int kRooms = 20;  // per side

// Twenty by twenty rooms of 5 x 5 m with doorways, each with a desk at a place of its own (a floor
// of identical rooms has no answer to find).
SyntheticWorld building() {
  SyntheticWorld w;
  w.room({0.0, 0.0}, {kSide_m, kSide_m});
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> desk(0.8, 3.4), door(0.5, 3.5);
  for (int i = 1; i < kRooms; ++i) {
    const double c = kRoom_m * i;
    for (int j = 0; j < kRooms; ++j) {
      const double lo = kRoom_m * j, hi = lo + kRoom_m;
      const double a = lo + door(rng), b = lo + door(rng);
      w.wall({c, lo}, {c, a});
      w.wall({c, a + 1.0}, {c, hi});
      w.wall({lo, c}, {b, c});
      w.wall({b + 1.0, c}, {hi, c});
    }
  }
  for (int i = 0; i < kRooms; ++i) {
    for (int j = 0; j < kRooms; ++j) {
      const Vec2 lo{kRoom_m * i + desk(rng), kRoom_m * j + desk(rng)};
      w.room(lo, {lo.x + 0.8, lo.y + 0.6});
    }
  }
  return w;
}

struct Building {
  ClassGrid grid;
  std::vector<Pose> truths;
  std::vector<std::vector<slam::correction::Ray>> trails;  // one laser keyframe each, its own frame
};

const Building& scene() {
  static const Building b = [] {
    const SyntheticWorld world = building();
    slam::GridGeometry geometry;
    geometry.resolution = 0.05;
    geometry.width = geometry.height = static_cast<int32_t>(kSide_m / geometry.resolution) + 1;
    Building out{ClassGrid::rasterise(world, geometry), {}, {}};
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> room(0, kRooms - 1);
    std::uniform_real_distribution<double> inside(1.0, 4.0), heading(-3.1, 3.1);
    SparseSensor laser;
    laser.beams = 360;
    laser.max_range_m = 8.0;
    laser.noise_m = 0.01;
    while (out.truths.size() < 8) {
      const Pose truth{kRoom_m * room(rng) + inside(rng), kRoom_m * room(rng) + inside(rng), heading(rng)};
      std::vector<Vec2> points;
      laser.observe(world, truth, truth, rng, points);
      if (points.size() < 200) continue;  // inside a desk
      std::vector<slam::correction::Ray> rays;
      for (const Vec2& p : points) rays.push_back({{0.0, 0.0}, p});
      out.truths.push_back(truth);
      out.trails.push_back(std::move(rays));
    }
    return out;
  }();
  return b;
}

PlacementJob whole_map_job(const Building& b, size_t k, bool new_map) {
  PlacementJob job;
  job.rays = b.trails[k];
  job.new_map = new_map;
  if (new_map) {
    job.grid_geometry = b.grid.geometry;
    job.grid_cells = b.grid.classes;
  }
  return job;
}

// The searcher with the building's maps prepared, and a job per keyframe of the scene.
std::vector<PlacementJob> prepared_jobs(const Building& b, PlacementSearcher& searcher,
                                        benchmark::State& state) {
  PlacementJob prepare = whole_map_job(b, 0, true);
  searcher.run(prepare);
  if (!prepare.map_ready) state.SkipWithError("map refused");
  std::vector<PlacementJob> jobs;
  for (size_t k = 0; k < b.truths.size(); ++k) jobs.push_back(whole_map_job(b, k, false));
  return jobs;
}

// Whole-map searches for robots whose place is unknown (odometry frame = keyframe frame), one per
// keyframe of the scene in each iteration: the time per search is the iteration's over their count.
void BM_PlacementSearch100m(benchmark::State& state) {
  const Building& b = scene();
  PlacementSearcher searcher{slam::correction::CorrectorOptions{}};
  std::vector<PlacementJob> jobs = prepared_jobs(b, searcher, state);
  int64_t found = 0, passed = 0, wrong = 0, nodes = 0;
  for (auto _ : state) {
    for (size_t k = 0; k < jobs.size(); ++k) {
      PlacementJob& job = jobs[k];
      searcher.run(job);
      if (!job.found) continue;
      // The whole map is searched at 20 cm here: right is within a hypothesis' confirmation reach.
      const bool right = slam::distance(job.found->pose.position(), b.truths[k].position()) <
                         slam::correction::CorrectorOptions{}.placement_agree_m;
      found += right ? 1 : 0;
      passed += job.passes ? 1 : 0;
      wrong += job.passes && !right ? 1 : 0;
      nodes += static_cast<int64_t>(job.found->nodes_scored);
    }
  }
  const auto n = static_cast<double>(state.iterations() * static_cast<int64_t>(jobs.size()));
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(jobs.size()));
  // Found: the best match is the true place; passed: distinct enough to count toward a placement.
  state.counters["found_share"] = static_cast<double>(found) / n;
  state.counters["passed_share"] = static_cast<double>(passed) / n;
  state.counters["wrong_passed"] = static_cast<double>(wrong);
  state.counters["nodes_per_search"] = static_cast<double>(nodes) / n;
}
BENCHMARK(BM_PlacementSearch100m)->Unit(benchmark::kMillisecond)->Iterations(1);

// Confirming a hypothesis (off by 0.1 m and 0.03 rad): the search around it on the fine map.
void BM_PlacementConfirm100m(benchmark::State& state) {
  const Building& b = scene();
  PlacementSearcher searcher{slam::correction::CorrectorOptions{}};
  std::vector<PlacementJob> jobs = prepared_jobs(b, searcher, state);
  for (size_t k = 0; k < jobs.size(); ++k) jobs[k].hypothesis = b.truths[k].compose({0.1, 0.0, 0.03});
  size_t next = 0;
  int64_t passed = 0;
  for (auto _ : state) {
    searcher.run(jobs[next]);
    passed += jobs[next].passes ? 1 : 0;
    next = (next + 1) % jobs.size();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["passed_share"] = static_cast<double>(passed) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_PlacementConfirm100m)->Unit(benchmark::kMillisecond);

// Preparing the searched maps from the 2001 x 2001-cell grid (done again when the map has grown).
void BM_PlacementMapPreparation100m(benchmark::State& state) {
  const Building& b = scene();
  PlacementSearcher searcher{slam::correction::CorrectorOptions{}};
  PlacementJob job = whole_map_job(b, 0, true);
  job.rays.clear();  // the map only
  for (auto _ : state) {
    searcher.run(job);
    benchmark::DoNotOptimize(job.map_ready);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PlacementMapPreparation100m)->Unit(benchmark::kMillisecond);

}  // namespace
