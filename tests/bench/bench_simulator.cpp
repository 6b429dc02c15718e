// Simulator throughput: a 0.1 s tick of 500 robots with 16 beams each in the office world, all
// reporting at 10 Hz (target: under 50 ms, half a core), and raw beam casts per second.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include "simulator/core/builtin_worlds.hpp"
#include "simulator/core/simulation.hpp"

namespace {

using slam::sim::Simulation;
using slam::sim::SimulationConfig;

Simulation office_fleet(size_t robots, int beams) {
  SimulationConfig c;
  c.dt = 0.1;  // one step per 10 Hz report period: every robot scans every step
  c.report_period = 0.1;
  c.sensor.beams = beams;
  c.random_walk = true;
  c.robot.max_linear = 0.5;
  auto world = slam::sim::builtin_world("office");
  auto sim = Simulation::create(std::move(*world), c);
  if (!sim) {
    std::fprintf(stderr, "bench setup: %s\n", sim.message().c_str());
    std::abort();
  }
  if (auto ids = sim->spawn_random(robots); !ids) {
    std::fprintf(stderr, "bench setup: %s\n", ids.message().c_str());
    std::abort();
  }
  for (int i = 0; i < 20; ++i) sim->step();  // warm up: every robot has reported, buffers sized
  return std::move(*sim);
}

// One iteration = one 0.1 s tick of the whole fleet, scans included.
void BM_FleetTick(benchmark::State& state) {
  const auto robots = static_cast<size_t>(state.range(0));
  Simulation sim = office_fleet(robots, static_cast<int>(state.range(1)));
  size_t reports = 0;
  for (auto _ : state) {
    const auto out = sim.step();
    reports += out.size();
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["ticks_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["reports_per_tick"] = static_cast<double>(reports) / static_cast<double>(state.iterations());
  // Share of one core needed to run this fleet in real time at 10 ticks per second (CPU time per
  // tick x 10; the target is below 0.5).
  state.counters["core_share_at_10Hz"] =
      benchmark::Counter(0.1 * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_FleetTick)->Args({500, 16})->Args({100, 16})->Args({500, 64})->Unit(benchmark::kMillisecond);

// Beams against walls and robot discs from random robot poses in the office fleet.
void BM_BeamCast(benchmark::State& state) {
  Simulation sim = office_fleet(500, 16);
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<size_t> pick(0, sim.robots().size() - 1);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  constexpr size_t kBatch = 1024;
  std::vector<std::pair<size_t, slam::Vec2>> beams(kBatch);
  for (auto& [robot, dir] : beams) {
    const double a = angle(rng);
    robot = pick(rng);
    dir = {std::cos(a), std::sin(a)};
  }
  for (auto _ : state) {
    double sum = 0.0;
    for (const auto& [robot, dir] : beams) {
      const auto& p = sim.robots()[robot].true_pose;
      sum += sim.cast({p.x, p.y}, dir, 4.0, robot);
    }
    benchmark::DoNotOptimize(sum);
  }
  state.counters["casts_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations() * kBatch), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_BeamCast);

}  // namespace
