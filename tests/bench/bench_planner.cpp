// bench_planner: the planner's speed targets on one deterministic 1024x1024 map (0.05 m cells):
// A* corner to corner (<= 20 ms), a sampling planner (FMT* + shortcutting: <= 50 ms, length within
// 10% of A*; RRTConnect and PRM* for comparison), frontier extraction (<= 5 ms), re-plans per
// second for a fleet of 100 robots, and one fleet coordination tick for 100 robots with the heap
// allocations it makes (counted by the operator new below: the steady state must make none).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <new>
#include <random>
#include <string>

#include "planner/core/fleet.hpp"
#include "planner/core/fleet_coordinator.hpp"
#include "planner/core/frontiers.hpp"
#include "planner/core/grid_astar.hpp"
#include "planner/core/path_planner.hpp"

namespace {
std::atomic<uint64_t> g_allocations{0};
}  // namespace

// Every heap allocation of the process is counted (the benchmarks read the count around the code
// they measure). Kept out of line: inlined, GCC pairs malloc() and free() with new and delete and warns.
[[gnu::noinline]] void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
[[gnu::noinline]] void operator delete(void* p) noexcept {
  std::free(p);
}
[[gnu::noinline]] void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

namespace slam::planner {
namespace {

constexpr uint32_t kSize = 1024;
constexpr double kResolution = 0.05;

void fill(std::vector<uint8_t>& cells, int x0, int y0, int x1, int y1, uint8_t v) {
  for (int y = std::max(0, y0); y <= std::min<int>(kSize - 1, y1); ++y) {
    for (int x = std::max(0, x0); x <= std::min<int>(kSize - 1, x1); ++x) {
      cells[static_cast<size_t>(y) * kSize + static_cast<size_t>(x)] = v;
    }
  }
}

// Seven long vertical walls, each with three 1.2 m doors, and random blocks up to 25% of the
// area that are cleared again around doors and corners so the map stays connected corner to
// corner; then inflation by two cells (0.1 m) as the mapper would flag it.
PlanningGrid make_map() {
  std::mt19937 rng(20240601);
  std::vector<uint8_t> cells(static_cast<size_t>(kSize) * kSize, kCellFree);
  struct Door {
    int x;
    int y;
  };
  std::vector<Door> doors;
  for (int i = 1; i <= 7; ++i) {
    const int x = i * 128;
    fill(cells, x, 0, x + 3, kSize - 1, kCellOccupied);
    for (int d = 0; d < 3; ++d) {
      doors.push_back({x, 40 + static_cast<int>(rng() % (kSize - 80))});
    }
  }
  const size_t target = cells.size() / 4;
  size_t occupied = static_cast<size_t>(std::count(cells.begin(), cells.end(), kCellOccupied));
  while (occupied < target) {
    const int w = 3 + static_cast<int>(rng() % 14);
    const int h = 3 + static_cast<int>(rng() % 14);
    const int x = static_cast<int>(rng() % kSize);
    const int y = static_cast<int>(rng() % kSize);
    for (int yy = y; yy < std::min<int>(kSize, y + h); ++yy) {
      for (int xx = x; xx < std::min<int>(kSize, x + w); ++xx) {
        uint8_t& c = cells[static_cast<size_t>(yy) * kSize + static_cast<size_t>(xx)];
        if (c != kCellOccupied) ++occupied;
        c = kCellOccupied;
      }
    }
  }
  // Doors: a 24-cell opening with a cleared apron so blocks cannot seal it.
  for (const Door& d : doors) fill(cells, d.x - 12, d.y - 12, d.x + 15, d.y + 12, kCellFree);
  fill(cells, 0, 0, 20, 20, kCellFree);
  fill(cells, kSize - 21, kSize - 21, kSize - 1, kSize - 1, kCellFree);
  std::vector<uint8_t> inflated = cells;
  for (int y = 0; y < static_cast<int>(kSize); ++y) {
    for (int x = 0; x < static_cast<int>(kSize); ++x) {
      if (cells[static_cast<size_t>(y) * kSize + static_cast<size_t>(x)] != kCellOccupied) continue;
      for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
          const int nx = x + dx;
          const int ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= static_cast<int>(kSize) || ny >= static_cast<int>(kSize) ||
              dx * dx + dy * dy > 4) {
            continue;
          }
          uint8_t& c = inflated[static_cast<size_t>(ny) * kSize + static_cast<size_t>(nx)];
          if ((c & kCellStateMask) == kCellFree) c |= kCellInflated;
        }
      }
    }
  }
  PlanningGrid grid;
  if (!grid.reset(
          GridGeometry{{0.0, 0.0}, kResolution, static_cast<int32_t>(kSize), static_cast<int32_t>(kSize)}, 1,
          0, std::move(inflated))) {
    return {};
  }
  return grid;
}

const PlanningGrid& bench_map() {
  static const PlanningGrid grid = make_map();
  return grid;
}

double blocked_fraction(const PlanningGrid& g) {
  const auto n = std::count_if(g.cells().begin(), g.cells().end(), cell_blocked);
  return static_cast<double>(n) / static_cast<double>(g.cells().size());
}

const Vec2 kStart{0.25, 0.25};
const Vec2 kGoal{kSize * kResolution - 0.25, kSize* kResolution - 0.25};

double astar_length() {
  static const double length = [] {
    PathPlanner p({});
    return p.plan(bench_map(), {kStart, kGoal, "astar", 10.0}).length_m;
  }();
  return length;
}

void BM_AstarCornerToCorner(benchmark::State& state) {
  const PlanningGrid& g = bench_map();
  PathPlanner planner({});
  PlanResult r;
  for (auto _ : state) {
    r = planner.plan(g, {kStart, kGoal, "astar", 10.0});
    benchmark::DoNotOptimize(r.path.data());
  }
  if (!r.ok()) state.SkipWithError(r.reason.c_str());
  state.counters["length_m"] = r.length_m;
  state.counters["waypoints"] = static_cast<double>(r.path.size());
  state.counters["blocked_fraction"] = blocked_fraction(g);
}

void BM_AstarSearchOnly(benchmark::State& state) {
  const PlanningGrid& g = bench_map();
  GridAstar astar;
  std::vector<Cell> cells;
  const Cell s = *g.cell_at(kStart);
  const Cell t = *g.cell_at(kGoal);
  for (auto _ : state) {
    benchmark::DoNotOptimize(astar.search(g, s, t, {}, cells));
  }
  state.counters["expanded"] = static_cast<double>(astar.last_expanded());
  state.counters["cost_m"] = astar.last_cost() * kResolution;
}

void BM_OmplCornerToCorner(benchmark::State& state, const char* algorithm, double budget_s) {
  const PlanningGrid& g = bench_map();
  PathPlanner planner({});
  const double reference = astar_length();
  double ratio_sum = 0.0;
  double ratio_worst = 0.0;
  int found = 0;
  int runs = 0;
  for (auto _ : state) {
    const PlanResult r = planner.plan(g, {kStart, kGoal, algorithm, budget_s});
    ++runs;
    if (r.ok()) {
      ++found;
      ratio_sum += r.length_m / reference;
      ratio_worst = std::max(ratio_worst, r.length_m / reference);
    }
  }
  state.counters["success_rate"] = runs > 0 ? static_cast<double>(found) / runs : 0.0;
  state.counters["length_ratio_to_astar"] = found > 0 ? ratio_sum / found : 0.0;
  state.counters["worst_length_ratio"] = ratio_worst;
}

void BM_FrontierExtraction(benchmark::State& state) {
  // Explored: everything within 20 m of the map centre; the rest unknown.
  std::vector<uint8_t> cells = bench_map().cells();
  for (uint32_t y = 0; y < kSize; ++y) {
    for (uint32_t x = 0; x < kSize; ++x) {
      const double dx = (x - 512.0) * kResolution;
      const double dy = (y - 512.0) * kResolution;
      if (dx * dx + dy * dy > 400.0) cells[static_cast<size_t>(y) * kSize + x] = kCellUnknown;
    }
  }
  PlanningGrid g;
  if (!g.reset(GridGeometry{{}, kResolution, static_cast<int32_t>(kSize), static_cast<int32_t>(kSize)}, 1, 0,
               std::move(cells))) {
    state.SkipWithError("bad grid");
    return;
  }
  FrontierMap frontiers;
  std::vector<FrontierCluster> clusters;
  for (auto _ : state) {
    frontiers.rebuild(g);
    frontiers.cluster(g, 4, clusters);
    benchmark::DoNotOptimize(clusters.data());
  }
  state.counters["frontier_cells"] = static_cast<double>(frontiers.count());
  state.counters["clusters"] = static_cast<double>(clusters.size());
}

void BM_FrontierPatchUpdate(benchmark::State& state) {
  PlanningGrid g = bench_map();
  FrontierMap frontiers;
  frontiers.rebuild(g);
  std::vector<FrontierCluster> clusters;
  const CellBox box{500, 500, 64, 64};
  for (auto _ : state) {
    frontiers.update(g, box);
    frontiers.cluster(g, 4, clusters);
    benchmark::DoNotOptimize(clusters.data());
  }
}

// One iteration = every one of 100 robots re-plans (A* + reduction) to its own random goal.
void BM_Replans100Robots(benchmark::State& state) {
  const PlanningGrid& g = bench_map();
  const double max_leg_m = static_cast<double>(state.range(0));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> any(0.0, kSize * kResolution);
  auto free_point = [&](Vec2 near, double radius) {
    for (;;) {
      Vec2 p = radius > 0 ? Vec2{near.x + (any(rng) / (kSize * kResolution) * 2 - 1) * radius,
                                 near.y + (any(rng) / (kSize * kResolution) * 2 - 1) * radius}
                          : Vec2{any(rng), any(rng)};
      const auto c = g.cell_at(p);
      if (c && !g.blocked(*c)) return p;
    }
  };
  std::vector<PathQuery> queries;
  for (int i = 0; i < 100; ++i) {
    const Vec2 s = free_point({}, 0.0);
    queries.push_back({s, free_point(s, max_leg_m), "astar", 10.0});
  }
  PathPlanner planner({});
  int ok = 0;
  for (auto _ : state) {
    for (const PathQuery& q : queries) ok += planner.plan(g, q).ok() ? 1 : 0;
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * 100);
  state.counters["replans_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * 100, benchmark::Counter::kIsRate);
  state.counters["ok_fraction"] = static_cast<double>(ok) / (static_cast<double>(state.iterations()) * 100.0);
}

// One coordination tick (FleetCoordinator::coordinate) for 100 robots on random routes of up to
// 10 m in the map's 25 m x 25 m lower-left quarter (close enough to hold each other up, with narrow
// stretches between the blocks). The robots stand still, so every tick decides the same: the
// steady state. Counts the heap allocations made inside coordinate() after a warm-up tick.
void BM_Coordinate100Robots(benchmark::State& state) {
  const PlanningGrid& g = bench_map();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> any(0.5, 25.0);
  const auto free_point = [&](Vec2 near, double radius) {
    for (;;) {
      const Vec2 p = radius > 0 ? Vec2{near.x + (any(rng) / 25.0 * 2 - 1) * radius,
                                       near.y + (any(rng) / 25.0 * 2 - 1) * radius}
                                : Vec2{any(rng), any(rng)};
      const auto c = g.cell_at(p);
      if (c && !g.blocked(*c)) return p;
    }
  };
  Fleet fleet{FleetConfig{}};
  CoordinationConfig config;
  config.replan_after_s = 1e6;  // re-planning around robots is an event, not the steady state
  config.one_way_sections = state.range(0) != 0;
  FleetCoordinator coordinator(config);
  for (int i = 0; i < 100; ++i) {
    const std::string id = "robot-" + std::to_string(i);
    const Vec2 at = free_point({}, 0.0);
    fleet.observe(id, at);
    coordinator.observe(id, at);
    if (!fleet.set_goal(id, Goal{static_cast<uint64_t>(i + 1), GoalMode::Planned, free_point(at, 10.0)})) {
      state.SkipWithError("goal refused");
      return;
    }
  }
  fleet.tick(g, 0);
  int64_t now = 0;
  coordinator.coordinate(fleet, g, now);  // warm-up: the buffers grow to their size here
  uint64_t allocations = 0;
  for (auto _ : state) {
    now += 50'000'000;
    const uint64_t before = g_allocations.load(std::memory_order_relaxed);
    coordinator.coordinate(fleet, g, now);
    allocations += g_allocations.load(std::memory_order_relaxed) - before;
  }
  state.counters["allocations_per_tick"] =
      static_cast<double>(allocations) / static_cast<double>(std::max<int64_t>(1, state.iterations()));
  state.counters["held"] = static_cast<double>(coordinator.held());
}

BENCHMARK(BM_AstarCornerToCorner)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_AstarSearchOnly)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK_CAPTURE(BM_OmplCornerToCorner, rrtconnect, "rrtconnect", 1.0)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(20)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true);
// FMT* stops when its tree reaches the goal: the budget is only a cap.
BENCHMARK_CAPTURE(BM_OmplCornerToCorner, fmtstar, "fmtstar", 1.0)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(20)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true);
BENCHMARK_CAPTURE(BM_OmplCornerToCorner, prmstar_200ms, "prmstar", 0.2)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5)
    ->Repetitions(1);
BENCHMARK(BM_FrontierExtraction)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_FrontierPatchUpdate)->Unit(benchmark::kMillisecond);
// Legs up to 10 m (typical goal and frontier trips) and anywhere on the map (worst case).
BENCHMARK(BM_Replans100Robots)->Arg(10)->Arg(0)->Unit(benchmark::kMillisecond);
// Argument: one-way sections off (the default) or on.
BENCHMARK(BM_Coordinate100Robots)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace slam::planner

BENCHMARK_MAIN();
