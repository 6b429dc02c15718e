// Mapper grid core throughput. Targets (one core): ray casting >= 200 M cells/s, ingest >= 1 M
// points/s, rebuild of 1 M stored observations at a new resolution <= 1 s; a re-render after one
// small loop closure costs what the closure moved, not what the store holds (full vs partial).
// Rays are 1-5 m long at 5 cm from many origins in a 40 m x 40 m area, like robots' range beams.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "mapper/core/compaction.hpp"
#include "mapper/core/observation_store.hpp"
#include "mapper/core/occupancy_grid.hpp"
#include "mapper/core/partial_rerender.hpp"
#include "mapper/core/ray_trace.hpp"
#include "mapper/core/rebuild.hpp"
#include "temp_dir.hpp"

namespace {

using slam::Vec2;
using slam::mapper::GridConfig;
using slam::mapper::ObservationStore;
using slam::mapper::ObservationView;
using slam::mapper::OccupancyGrid;

GridConfig area_config(double resolution) {
  GridConfig c;
  c.resolution = resolution;
  c.origin_x = -20.0;
  c.origin_y = -20.0;
  c.width_m = 40.0;
  c.height_m = 40.0;
  c.inflation_radius = 0.2;
  return c;
}

template <class T>
T must(slam::Result<T> r, const char* what) {
  if (!r) {
    std::fprintf(stderr, "bench setup (%s): %s\n", what, r.message().c_str());
    std::abort();
  }
  return std::move(*r);
}

struct Scan {
  Vec2 origin;
  std::vector<Vec2> hits;
  std::vector<Vec2> misses;
};

// `beams` rays per scan, 1-5 m long, every fourth one a miss (nothing seen up to max range).
std::vector<Scan> make_scans(int count, int beams, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(-14.0, 14.0);
  std::uniform_real_distribution<double> range(1.0, 5.0);
  std::vector<Scan> scans(static_cast<size_t>(count));
  for (Scan& s : scans) {
    s.origin = {pos(rng), pos(rng)};
    for (int b = 0; b < beams; ++b) {
      const double a = 2.0 * std::numbers::pi * b / beams;
      const double r = range(rng);
      const Vec2 p{s.origin.x + r * std::cos(a), s.origin.y + r * std::sin(a)};
      (b % 4 == 3 ? s.misses : s.hits).push_back(p);
    }
  }
  return scans;
}

// Pure traversal: cells visited per second by trace_ray with a trivial visitor.
void BM_TraceRay(benchmark::State& state) {
  const int32_t side = 800;  // 40 m at 5 cm
  std::vector<uint8_t> cells(static_cast<size_t>(side) * side, 0);
  std::mt19937 rng(7);
  std::uniform_int_distribution<int32_t> pos(100, side - 100);
  std::uniform_real_distribution<double> len(20.0, 100.0);  // 1-5 m
  struct Ray {
    int32_t x0, y0, x1, y1;
  };
  std::vector<Ray> rays(4096);
  for (Ray& r : rays) {
    r.x0 = pos(rng);
    r.y0 = pos(rng);
    const double a = std::uniform_real_distribution<double>(0, 2 * std::numbers::pi)(rng);
    const double l = len(rng);
    r.x1 = r.x0 + static_cast<int32_t>(std::lround(l * std::cos(a)));
    r.y1 = r.y0 + static_cast<int32_t>(std::lround(l * std::sin(a)));
  }
  int64_t total = 0;
  for (auto _ : state) {
    for (const Ray& r : rays)
      total +=
          slam::mapper::trace_ray(r.x0, r.y0, r.x1, r.y1, side, side, false, [&](size_t i) { ++cells[i]; });
    benchmark::DoNotOptimize(cells.data());
  }
  state.counters["cells_per_s"] = benchmark::Counter(static_cast<double>(total), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_TraceRay);

// Full ingest through the grid core: validation, hits, miss updates with one-update-per-cell,
// class and inflation upkeep. Reports points/s and cells/s.
void BM_IntegrateScans(benchmark::State& state) {
  const int beams = static_cast<int>(state.range(0));
  const std::vector<Scan> scans = make_scans(512, beams, 11);
  OccupancyGrid grid = must(OccupancyGrid::create(area_config(0.05)), "grid");
  int64_t points = 0;
  int64_t cells = 0;
  size_t k = 0;
  for (auto _ : state) {
    const Scan& s = scans[k++ % scans.size()];
    ObservationView v{s.origin.x, s.origin.y, 0.0, false, s.hits, s.misses};
    auto r = grid.integrate(v);
    if (!r) state.SkipWithError(r.message().c_str());
    cells += r->cells_traced;
    points += static_cast<int64_t>(s.hits.size() + s.misses.size());
  }
  state.counters["points_per_s"] =
      benchmark::Counter(static_cast<double>(points), benchmark::Counter::kIsRate);
  state.counters["cells_per_s"] = benchmark::Counter(static_cast<double>(cells), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_IntegrateScans)->Arg(4)->Arg(360);

// The store of 1 M observations (4 hits each, a v1 robot's message) is written once per process.
class StoreFixture {
 public:
  static constexpr int64_t kObservations = 1'000'000;

  StoreFixture() {
    ObservationStore store = must(ObservationStore::open(path_, {4096}), "store");
    const std::vector<Scan> scans = make_scans(4096, 4, 23);
    for (int64_t i = 0; i < kObservations; ++i) {
      const Scan& s = scans[static_cast<size_t>(i) % scans.size()];
      ObservationView v{s.origin.x, s.origin.y, 0.0, false, s.hits, s.misses};
      if (!store.append(i % 2 ? "r1" : "r2", static_cast<uint64_t>(i), i, 0, v)) std::abort();
    }
    if (!store.flush()) std::abort();
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  slam::testkit::TempDir dir_{"bench-mapper"};  // the store and its -wal/-shm files go with it
  std::filesystem::path path_ = dir_ / "store.db";
};

const StoreFixture& stored_observations() {
  static const StoreFixture fixture;
  return fixture;
}

void BM_Rebuild1M(benchmark::State& state) {
  ObservationStore store = must(ObservationStore::open(stored_observations().path()), "reopen");
  const GridConfig config = area_config(static_cast<double>(state.range(0)) / 100.0);
  int64_t observations = 0;
  for (auto _ : state) {
    slam::mapper::RebuildStats stats;
    auto grid = slam::mapper::rebuild_grid(config, store, &stats);
    if (!grid || stats.observations != StoreFixture::kObservations) state.SkipWithError("rebuild failed");
    observations += stats.observations;
    benchmark::DoNotOptimize(grid->classes().data());
  }
  state.counters["observations_per_s"] =
      benchmark::Counter(static_cast<double>(observations), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Rebuild1M)->Arg(10)->Arg(5)->Unit(benchmark::kMillisecond)->Iterations(3);

// Reading the store alone: the floor under any rebuild.
void BM_StoreScan1M(benchmark::State& state) {
  ObservationStore store = must(ObservationStore::open(stored_observations().path()), "reopen");
  int64_t rows = 0;
  for (auto _ : state) {
    const slam::Status s = store.for_each([&](const slam::mapper::ObservationRecord& r) {
      rows += 1;
      benchmark::DoNotOptimize(r.obs.hits.data());
    });
    if (!s) state.SkipWithError(s.message().c_str());
  }
  state.counters["rows_per_s"] = benchmark::Counter(static_cast<double>(rows), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_StoreScan1M)->Unit(benchmark::kMillisecond)->Iterations(3);

// A fleet's store: 10 robots random-walking over 60 m x 60 m at 0.1 m per observation, 16 beams of
// 1-5 m each (the simulator's default scan), a keyframe every 15 observations of a robot (what the
// issue-39 run stored: 370 000 observations, 24 500 keyframes). Keyframe corrections start at identity.
class FleetStore {
 public:
  static constexpr int kRobots = 10;
  static constexpr int kPerKeyframe = 15;

  explicit FleetStore(int64_t observations) : observations_(observations) {
    ObservationStore store = must(ObservationStore::open(path_, {4096}), "store");
    std::mt19937 rng(31);
    std::uniform_real_distribution<double> turn(-0.3, 0.3);
    std::uniform_real_distribution<double> range(1.0, 5.0);
    struct Walker {
      double x, y, heading;
    };
    std::vector<Walker> walkers;
    for (int r = 0; r < kRobots; ++r) walkers.push_back({-25.0 + 5.0 * r, -25.0 + 5.0 * r, 0.3 * r});
    std::vector<Vec2> hits, misses;
    for (int64_t i = 0; i < observations; ++i) {
      const int r = static_cast<int>(i % kRobots);
      const int64_t n = i / kRobots;  // this robot's observation number
      Walker& w = walkers[static_cast<size_t>(r)];
      w.heading += turn(rng);
      w.x += 0.1 * std::cos(w.heading);
      w.y += 0.1 * std::sin(w.heading);
      if (std::abs(w.x) > 27.0 || std::abs(w.y) > 27.0)
        w.heading += std::numbers::pi;  // turn back at the walls
      w.x = std::clamp(w.x, -27.0, 27.0);
      w.y = std::clamp(w.y, -27.0, 27.0);
      hits.clear();
      misses.clear();
      for (int b = 0; b < 16; ++b) {
        const double a = w.heading + 2.0 * std::numbers::pi * b / 16;
        const double d = range(rng);
        (b % 4 == 3 ? misses : hits).push_back({w.x + d * std::cos(a), w.y + d * std::sin(a)});
      }
      const auto keyframe = static_cast<slam::mapper::KeyframeId>(1 + r * 1'000'000 + n / kPerKeyframe);
      if (n % kPerKeyframe == 0) keyframes_.push_back(keyframe);
      const ObservationView v{w.x, w.y, w.heading, true, hits, misses};
      if (!store.append(std::string("r") + std::to_string(r), static_cast<uint64_t>(n), i, keyframe, v))
        std::abort();
    }
    if (!store.flush()) std::abort();
  }
  const std::filesystem::path& path() const { return path_; }
  int64_t observations() const { return observations_; }
  // A keyframe in the middle of the store (what a loop closure moves).
  slam::mapper::KeyframeId closed_keyframe() const { return keyframes_[keyframes_.size() / 2]; }
  // The corrections after the closure: that keyframe 5 cm off, the rest where they are drawn.
  slam::mapper::KeyframeCorrections after_closure() const {
    slam::mapper::KeyframeCorrections c;
    c.set(closed_keyframe(), slam::Pose{0.05, -0.03, 0.002});
    return c;
  }

 private:
  int64_t observations_;
  std::vector<slam::mapper::KeyframeId> keyframes_;
  slam::testkit::TempDir dir_{"bench-mapper-fleet"};
  std::filesystem::path path_ = dir_ / "fleet.db";
};

const FleetStore& fleet_store(int64_t observations) {
  static const FleetStore small(100'000);
  if (observations == small.observations()) return small;
  static const FleetStore large(400'000);
  return large;
}

GridConfig fleet_config() {
  GridConfig c = area_config(0.05);
  c.origin_x = -32.0;
  c.origin_y = -32.0;
  c.width_m = 64.0;
  c.height_m = 64.0;
  return c;
}

// Today's re-render before issue 39: the whole store replayed into a new grid with the corrections.
void BM_RerenderFull(benchmark::State& state) {
  const FleetStore& fleet = fleet_store(state.range(0));
  ObservationStore store = must(ObservationStore::open(fleet.path()), "reopen");
  const slam::mapper::KeyframeCorrections corrections = fleet.after_closure();
  int64_t replayed = 0;
  for (auto _ : state) {
    slam::mapper::RebuildStats stats;
    auto grid = slam::mapper::rebuild_grid(fleet_config(), store, &stats, corrections);
    if (!grid || stats.observations != fleet.observations()) state.SkipWithError("rebuild failed");
    replayed = stats.observations;
    benchmark::DoNotOptimize(grid->classes().data());
  }
  state.counters["observations_replayed"] = static_cast<double>(replayed);
}
BENCHMARK(BM_RerenderFull)->Arg(100'000)->Arg(400'000)->Unit(benchmark::kMillisecond)->Iterations(3);

// The same closure re-rendered partially: the plan (map loop), the tiles drawn from the store (worker),
// the tiles copied into the grid (map loop). Each iteration redraws the same closure.
void BM_RerenderPartial(benchmark::State& state) {
  using Clock = std::chrono::steady_clock;
  const FleetStore& fleet = fleet_store(state.range(0));
  ObservationStore store = must(ObservationStore::open(fleet.path()), "reopen");
  slam::mapper::FootprintIndex index;
  OccupancyGrid grid =
      must(slam::mapper::rebuild_grid(fleet_config(), store, nullptr, {}, &index), "rebuild");
  const slam::mapper::KeyframeCorrections corrections = fleet.after_closure();
  double plan_s = 0, render_s = 0, redraw_s = 0;
  int64_t replayed = 0, rows = 0;
  size_t tiles = 0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    slam::mapper::RerenderDecision d = plan_rerender(index, corrections, grid, {});
    const auto t1 = Clock::now();
    if (d.kind != slam::mapper::RerenderDecision::Kind::Partial) state.SkipWithError("not partial");
    tiles = d.plan.tiles.size();
    auto render = must(slam::mapper::render_tiles(std::move(d.plan), store), "render");
    const auto t2 = Clock::now();
    grid.redraw(render.canvas);
    const auto t3 = Clock::now();
    plan_s += std::chrono::duration<double>(t1 - t0).count();
    render_s += std::chrono::duration<double>(t2 - t1).count();
    redraw_s += std::chrono::duration<double>(t3 - t2).count();
    replayed = render.replayed;
    rows = render.rows_read;
  }
  const auto n = static_cast<double>(state.iterations());
  state.counters["plan_ms"] = 1e3 * plan_s / n;
  state.counters["render_ms"] = 1e3 * render_s / n;
  state.counters["redraw_ms"] = 1e3 * redraw_s / n;
  state.counters["observations_replayed"] = static_cast<double>(replayed);
  state.counters["rows_read"] = static_cast<double>(rows);
  state.counters["tiles"] = static_cast<double>(tiles);
  state.counters["index_kb"] = static_cast<double>(index.memory_bytes()) / 1024.0;
}
BENCHMARK(BM_RerenderPartial)->Arg(100'000)->Arg(400'000)->Unit(benchmark::kMillisecond)->Iterations(10);

// Issue 39 item 3: the fleet store compacted but for its newest 40 000 rows (a copy; what a retention
// leaves raw), then rebuilt from the baseline and those rows, and one closure re-rendered partially.
// Counters: the store's size before and after (pages in use), the compaction's time, the rebuild's.
void BM_CompactedRebuild(benchmark::State& state) {
  using Clock = std::chrono::steady_clock;
  constexpr int64_t kRaw = 40'000;
  const FleetStore& fleet = fleet_store(state.range(0));
  const slam::testkit::TempDir dir{"bench-mapper-compact"};
  const std::filesystem::path copy = dir / "compacted.db";
  std::filesystem::copy_file(fleet.path(), copy);
  ObservationStore store = must(ObservationStore::open(copy), "copy");
  const double mb = 1024.0 * 1024.0;
  const double before_mb = static_cast<double>(must(store.used_bytes(), "size")) / mb;
  const auto t0 = Clock::now();
  const auto report =
      must(slam::mapper::compact_store(fleet_config(), store, {}, fleet.observations() - kRaw), "compact");
  const double compact_s = std::chrono::duration<double>(Clock::now() - t0).count();
  double rebuild_s = 0.0, partial_s = 0.0;
  for (auto _ : state) {
    const auto t1 = Clock::now();
    slam::mapper::FootprintIndex index;
    slam::mapper::RebuildStats stats;
    OccupancyGrid grid =
        must(slam::mapper::rebuild_grid(fleet_config(), store, &stats, {}, &index), "rebuild");
    const auto t2 = Clock::now();
    if (stats.observations != kRaw) state.SkipWithError("rebuild replayed the wrong rows");
    slam::mapper::KeyframeCorrections moved;  // a keyframe among the raw ones, 5 cm off
    moved.set(index.groups()[index.groups().size() / 2].keyframe, slam::Pose{0.05, -0.03, 0.002});
    slam::mapper::RerenderDecision d = plan_rerender(index, moved, grid, {});
    if (d.kind != slam::mapper::RerenderDecision::Kind::Partial) state.SkipWithError("not partial");
    auto render = must(slam::mapper::render_tiles(std::move(d.plan), store), "render");
    grid.redraw(render.canvas);
    const auto t3 = Clock::now();
    rebuild_s += std::chrono::duration<double>(t2 - t1).count();
    partial_s += std::chrono::duration<double>(t3 - t2).count();
    benchmark::DoNotOptimize(grid.classes().data());
  }
  const auto n = static_cast<double>(state.iterations());
  state.counters["store_mb_before"] = before_mb;
  state.counters["store_mb_after"] = static_cast<double>(must(store.used_bytes(), "size")) / mb;
  state.counters["compact_ms"] = 1e3 * compact_s;
  state.counters["rebuild_ms"] = 1e3 * rebuild_s / n;
  state.counters["partial_ms"] = 1e3 * partial_s / n;
  state.counters["rows_deleted"] = static_cast<double>(report.rows_deleted);
  state.counters["tiles"] = static_cast<double>(report.tiles);
}
BENCHMARK(BM_CompactedRebuild)->Arg(100'000)->Arg(400'000)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
