// Mapper grid core throughput. Targets (one core): ray casting >= 200 M cells/s, ingest >= 1 M
// points/s, rebuild of 1 M stored observations at a new resolution <= 1 s.
// Rays are 1-5 m long at 5 cm from many origins in a 40 m x 40 m area, like robots' range beams.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "mapper/core/observation_store.hpp"
#include "mapper/core/occupancy_grid.hpp"
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

}  // namespace

BENCHMARK_MAIN();
