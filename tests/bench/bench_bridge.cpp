// The bridge core's cost per second of fleet input with one Foxglove client subscribed to every
// channel (target: <= 10 % of a core at 1000 robots x 10 Hz). One iteration is one simulated second:
// 1000 robots each send 10 states and 10 observations of 16 points, the mapper 10 tile patches
// (40 changed 32 x 32 tiles each, scattered over the grid as an exploring fleet's are) of a
// 1024 x 1024 grid, 1000 path updates, 8 heartbeats; the service loop runs every 20 ms (50 times)
// and publishes what is due at the default periods. These are the per-robot rates the bridge took
// before the gateways' fleet digests (each robot's state 5 times a second, its points once): an upper
// bound of the core's work. The frames are built as for a real client and counted, not sent: the
// WebSocket write and the DDS sample conversion are not in the figure.
// Run: build/bin/bench_bridge --benchmark_format=json
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "bridge/core/foxglove_face.hpp"

namespace {

using namespace slam;
using namespace slam::bridge;

constexpr int kRobots = 1000;
constexpr int kRateHz = 10;
constexpr int kLoopsPerSecond = 50;
constexpr int kHits = 16;
constexpr int32_t kGridSide = 1024;
constexpr int kTilesPerPatch = 40;
constexpr int64_t kSecondNs = 1'000'000'000;

class CountingSinks : public FrameSink, public OperatorSink {
 public:
  void send_text(ClientId, const std::string& t) override { bytes += t.size(); }
  void send_binary(ClientId, const std::string& b) override {
    bytes += b.size();
    ++messages;
  }
  void send_goal(const GoalCommand&) override {}
  void request_path(const PathCall&) override {}
  size_t bytes = 0;
  size_t messages = 0;
};

void BM_BridgeOneSecondOfFleetInput(benchmark::State& state) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(1.0, 50.0);
  Counters counters;
  CountingSinks sinks;
  FoxgloveFace face(ChannelPeriods{}, "bench", sinks, sinks, counters);
  BridgeOptions options;
  FleetModel fleet(options.points_per_robot);
  MapView map;
  face.connect(1);
  for (const auto& c : channel_table()) {
    const std::string subscribe = "{\"op\":\"subscribe\",\"subscriptions\":[{\"id\":" + std::to_string(c.id) +
                                  ",\"channelId\":" + std::to_string(c.id) + "}]}";
    face.receive_text(1, subscribe);
  }

  msg::GridSnapshot snapshot{1, 0, 0, msg::GridInfo{kGridSide, kGridSide, 0.05, {0, 0}, 0.0},
                             std::vector<uint8_t>(static_cast<size_t>(kGridSide) * kGridSide, 1)};
  if (!map.ingest(std::move(snapshot))) {
    state.SkipWithError("snapshot refused");
    return;
  }
  const uint32_t tiles_total = (kGridSide / 32) * (kGridSide / 32);
  msg::GridTiles patch{1, 0, 0, 32, 0, {}, std::vector<uint8_t>(kTilesPerPatch * 32 * 32, 2)};
  uint64_t version = 0;

  std::vector<std::string> ids;
  std::vector<Vec2> hits(kHits);
  for (int r = 0; r < kRobots; ++r) ids.push_back("sim-" + std::to_string(r + 1));
  std::vector<Vec2> waypoints(10);

  int64_t now = 0;
  const int per_loop = kRobots * kRateHz / kLoopsPerSecond;  // samples of each kind per loop turn
  size_t robot = 0;
  for (auto _ : state) {
    for (int loop = 0; loop < kLoopsPerSecond; ++loop) {
      for (int i = 0; i < per_loop; ++i, robot = (robot + 1) % kRobots) {
        const double x = coord(rng), y = coord(rng);
        fleet.ingest(msg::RobotPose{ids[robot], Pose{x, y, 0.3}, true, true, now});
        for (auto& h : hits) h = {x + coord(rng) / 10, y + coord(rng) / 10};
        fleet.ingest(ObservationInput{ids[robot], hits});
      }
      for (int i = 0; i < kRobots / kLoopsPerSecond; ++i) {
        const std::string& id = ids[static_cast<size_t>(rng()) % kRobots];
        for (auto& w : waypoints) w = {coord(rng), coord(rng)};
        fleet.ingest(msg::RobotPath{id, 0, msg::GoalMode::Explore, msg::GoalStatus::Active, waypoints.back(),
                                    waypoints, 0, ""});
      }
      if (loop % (kLoopsPerSecond / kRateHz) == 0) {
        patch.version = ++version;
        patch.tiles.clear();
        for (int t = 0; t < kTilesPerPatch; ++t)
          patch.tiles.push_back(static_cast<uint32_t>(rng()) % tiles_total);
        std::sort(patch.tiles.begin(), patch.tiles.end());
        patch.tiles.erase(std::unique(patch.tiles.begin(), patch.tiles.end()), patch.tiles.end());
        patch.data.resize(patch.tiles.size() * 32 * 32, 2);
        if (!map.ingest(patch)) state.SkipWithError("patch refused");
      }
      if (loop % (kLoopsPerSecond / 8) == 0)
        fleet.ingest(msg::Heartbeat{"mapper", "vm:1", 1, "vm", 0, 1.0, msg::ServiceState::Running, {}}, now);
      now += kSecondNs / kLoopsPerSecond;
      face.publish(fleet, map, now, now);
    }
  }
  // Each iteration is one second of input: its time is the share of a core the bridge needs.
  state.counters["out_MB_per_s"] =
      benchmark::Counter(static_cast<double>(sinks.bytes) / 1e6 / static_cast<double>(state.iterations()));
  state.counters["messages_per_s"] =
      benchmark::Counter(static_cast<double>(sinks.messages) / static_cast<double>(state.iterations()));
}
BENCHMARK(BM_BridgeOneSecondOfFleetInput)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
