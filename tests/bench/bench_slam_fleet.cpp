// bench_slam_fleet: the mapper's map loop with pose correction on at fleet load, without DDS. A
// Mapper (SQLite store in a temporary directory) and its CorrectionStage are fed what
// bench_pipeline's simulator sends: N robots (default 1000) at 10 Hz driving at 0.5 m/s through an
// 80 m x 80 m world of 8 m rooms with 1.2 m doors, 9 beams of up to 12 m per message (v1: hits only,
// odometry = truth). The loop runs as MapperNode::run_once does: each 100 ms the observations of that
// period go into the stage, then step() (match, finalise, re-render), then the store commit; paced in
// real time, so the match worker and the rebuild worker run alongside as in the process.
// SLAM_BENCH_FLEET_PACED=0: not paced; each period waits until every closed keyframe is finalised,
// which gives the CPU cost of correcting everything on a machine too loaded to keep real time.
// Figures (per simulated second): CPU of the loop thread and of the whole process (workers included)
// as a share of one core, keyframes closed and finalised, and at the end what correction holds back:
// observations in open keyframes (by design: a keyframe closes after 0.4 m of travel) and in closed
// keyframes not yet matched (late), plus keyframes placed by odometry alone (the schedule's overflow).
// Run: build/bin/bench_slam_fleet   (SLAM_BENCH_FLEET_ROBOTS=N, SLAM_BENCH_FLEET_SECONDS=S, default 20)
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <numbers>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "mapper/core/correction_stage.hpp"
#include "mapper/core/mapper.hpp"
#include "synthetic_world.hpp"
#include "temp_dir.hpp"

namespace {

using slam::Pose;
using slam::Vec2;
using slam::testkit::SparseSensor;
using slam::testkit::SyntheticWorld;

constexpr double kRoom_m = 8.0;
constexpr int kRooms = 10;  // per side: 80 m
constexpr double kDoor_m = 1.2;
constexpr double kSpeed_mps = 0.5;
constexpr double kRateHz = 10.0;
constexpr int64_t kPeriodNs = 100'000'000;  // the mapper's patch period: one loop pass

int env_int(const char* name, int fallback) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0' ? std::atoi(v) : fallback;
}

// Rooms with a door in the middle of every inner wall segment.
SyntheticWorld rooms() {
  SyntheticWorld w;
  const double side = kRoom_m * kRooms;
  w.room({0.0, 0.0}, {side, side});
  for (int i = 1; i < kRooms; ++i) {
    const double c = kRoom_m * i;
    for (int j = 0; j < kRooms; ++j) {
      const double lo = kRoom_m * j, mid = lo + kRoom_m / 2.0, hi = lo + kRoom_m;
      w.wall({c, lo}, {c, mid - kDoor_m / 2.0});
      w.wall({c, mid + kDoor_m / 2.0}, {c, hi});
      w.wall({lo, c}, {mid - kDoor_m / 2.0, c});
      w.wall({mid + kDoor_m / 2.0, c}, {hi, c});
    }
  }
  return w;
}

struct Message {
  uint32_t robot = 0;
  Pose pose;
  std::vector<Vec2> hits;
};

// One period's messages of every robot; robots turn away (a random new heading) before a wall.
class Fleet {
 public:
  Fleet(const SyntheticWorld& world, int robots, uint32_t seed) : world_(world), rng_(seed) {
    std::uniform_real_distribution<double> in_room(1.0, kRoom_m - 1.0),
        heading(-std::numbers::pi, std::numbers::pi);
    std::uniform_int_distribution<int> room(0, kRooms - 1);
    for (int r = 0; r < robots; ++r) {
      poses_.push_back(
          {kRoom_m * room(rng_) + in_room(rng_), kRoom_m * room(rng_) + in_room(rng_), heading(rng_)});
      names_.push_back("robot" + std::to_string(r));
    }
    sensor_.beams = 9;
    sensor_.max_range_m = 12.0;
    sensor_.noise_m = 0.01;
  }
  const std::string& name(uint32_t r) const { return names_[r]; }

  void period(std::vector<Message>& out) {
    std::uniform_real_distribution<double> heading(-std::numbers::pi, std::numbers::pi);
    const double step = kSpeed_mps / kRateHz;
    out.resize(poses_.size());
    for (uint32_t r = 0; r < poses_.size(); ++r) {
      Pose& p = poses_[r];
      for (int tries = 0; tries < 8; ++tries) {
        const auto ahead = world_.cast(p.position(), p.theta, 0.6);
        if (!ahead) break;
        p.theta = heading(rng_);
      }
      p = p.compose(Pose{step, 0.0, 0.0});
      Message& m = out[r];
      m.robot = r;
      m.pose = p;
      m.hits.clear();
      sensor_.observe(world_, p, Pose{}, rng_, m.hits);
    }
  }

 private:
  const SyntheticWorld& world_;
  std::mt19937 rng_;
  SparseSensor sensor_;
  std::vector<Pose> poses_;
  std::vector<std::string> names_;
};

double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

double process_cpu_s() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-6;
}

void BM_MapLoopFleet(benchmark::State& state) {
  const int robots = env_int("SLAM_BENCH_FLEET_ROBOTS", 1000);
  const int seconds = env_int("SLAM_BENCH_FLEET_SECONDS", 20);
  const bool slam = state.range(0) != 0;
  const bool paced = env_int("SLAM_BENCH_FLEET_PACED", 1) != 0;
  const SyntheticWorld world = rooms();
  slam::testkit::TempDir dir("bench-slam-fleet");
  slam::mapper::MapperOptions options;
  options.store = (dir.path() / "map.db").string();
  options.grid.origin_x = options.grid.origin_y = -5.0;  // as bench_pipeline: 90 m at 5 cm, never grows
  options.grid.width_m = options.grid.height_m = 90.0;
  options.slam = slam ? "on" : "off";
  slam::Counters counters;
  auto mapper = slam::mapper::Mapper::create(options, counters, 1, [] {});
  if (!mapper) {
    state.SkipWithError(mapper.message().c_str());
    return;
  }
  slam::correction::CorrectorOptions slam_options;
  slam_options.match_threads = 1;  // as the mapper
  slam::mapper::CorrectionStage stage(slam, slam_options);
  Fleet fleet(world, robots, 7);
  std::vector<Message> messages;
  std::vector<uint64_t> seqs(static_cast<size_t>(robots), 0);
  const std::vector<Vec2> no_misses;

  for (auto _ : state) {
    const double loop0 = thread_cpu_s(), process0 = process_cpu_s();
    const auto wall0 = std::chrono::steady_clock::now();
    int64_t stamp_ns = 1'700'000'000'000'000'000;
    const int periods = seconds * static_cast<int>(kRateHz);
    double generating_s = 0.0;  // the simulated fleet's own CPU, not the mapper's
    for (int t = 0; t < periods; ++t) {
      const double generate0 = thread_cpu_s();
      fleet.period(messages);
      generating_s += thread_cpu_s() - generate0;
      stamp_ns += kPeriodNs;
      const auto mono = static_cast<int64_t>(t) * kPeriodNs;
      (*mapper)->poll_rebuild();
      for (const Message& m : messages) {
        const slam::mapper::ObservationView view{m.pose.x, m.pose.y, m.pose.theta, false, m.hits, no_misses};
        stage.add(**mapper, {fleet.name(m.robot), ++seqs[m.robot], stamp_ns, view, 0, Pose{}}, mono);
      }
      stage.step(**mapper, stamp_ns, mono);
      // Unpaced: every keyframe closed so far is finalised before the next period (the cost of all
      // of it, whatever the machine's load; extra passes only land results).
      while (!paced && stage.stats().backlog > 0) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        stage.step(**mapper, stamp_ns, mono);
      }
      (*mapper)->commit();
      if (paced) std::this_thread::sleep_until(wall0 + std::chrono::nanoseconds(kPeriodNs * (t + 1)));
    }
    const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    const auto& st = stage.stats();
    auto& c = state.counters;
    c["robots"] = robots;
    c["loop_cpu_pct"] = 100.0 * (thread_cpu_s() - loop0 - generating_s) / seconds;
    c["process_cpu_pct"] = 100.0 * (process_cpu_s() - process0 - generating_s) / seconds;
    c["wall_over_sim"] = wall_s / seconds;
    c["observations_per_s"] = static_cast<double>(counters.get("observations").load()) / seconds;
    c["keyframes_per_s"] = static_cast<double>(st.keyframes) / seconds;
    c["matched_per_s"] = static_cast<double>(st.matched) / seconds;
    c["placed_by_odometry"] = static_cast<double>(st.placed_by_odometry);
    c["ties_tried"] = static_cast<double>(st.ties_tried);
    c["optimisations"] = static_cast<double>(st.optimisations);
    c["rebuilds"] = static_cast<double>(counters.get("rebuilds").load());
    c["backlog_keyframes_end"] = static_cast<double>(st.backlog);
    c["held_end"] = static_cast<double>(stage.held_observations());
    c["held_open_end"] = static_cast<double>(st.open_messages);
    std::fprintf(
        stderr,
        "bench_slam_fleet: %d robots, slam %s, %d s%s: loop thread %.0f %% of a core, process %.0f %%, "
        "wall/sim %.2f; %.0f obs/s integrated, %.0f keyframes/s (%.0f matched/s), %.0f placed by "
        "odometry, %.0f optimisations, %.0f rebuilds; at the end %.0f keyframes closed and not "
        "finalised, %.0f observations held (%.0f in open keyframes, %.0f waiting for a match)\n",
        robots, slam ? "on" : "off", seconds, paced ? "" : " (unpaced)", c["loop_cpu_pct"].value,
        c["process_cpu_pct"].value, c["wall_over_sim"].value, c["observations_per_s"].value,
        c["keyframes_per_s"].value, c["matched_per_s"].value, c["placed_by_odometry"].value,
        c["optimisations"].value, c["rebuilds"].value, c["backlog_keyframes_end"].value, c["held_end"].value,
        c["held_open_end"].value, c["held_end"].value - c["held_open_end"].value);
  }
}
BENCHMARK(BM_MapLoopFleet)->Arg(1)->Arg(0)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
