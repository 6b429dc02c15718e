// Per-message cost of the gateway's inbound codecs: v1 binary decode and each v2 JSON decode,
// with the output reused as the gateway does. Items/s = messages/s per core.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "protocol/topic.hpp"
#include "protocol/v1_codec.hpp"
#include "protocol/v2_robot_decode.hpp"
#include "protocol/v2_server_codec.hpp"

namespace {

using namespace slam::protocol;

std::span<const std::uint8_t> as_bytes(const std::string& text) {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

// A v1 adv message with `n` obstacle points on a circle, as a 2019 robot sends it.
std::vector<std::uint8_t> v1_payload(int n) {
  std::vector<Point> obstacles;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * std::numbers::pi * i / n;
    obstacles.push_back({3.0 + 2.0 * std::cos(a), -1.0 + 2.0 * std::sin(a)});
  }
  std::vector<std::uint8_t> payload;
  if (!encode_v1_adv({3.0, -1.0}, obstacles, 100.0, payload)) std::abort();
  return payload;
}

// A v2 scan with `n` beams over 270 degrees, every fifth beam without a return.
std::string v2_scan(int n) {
  std::string ranges;
  for (int i = 0; i < n; ++i) {
    if (i > 0) ranges += ',';
    ranges +=
        i % 5 == 0 ? std::string("null") : fmt::format("{:.3f}", 0.5 + 3.0 * std::abs(std::sin(i * 0.05)));
  }
  return fmt::format(R"({{"pose":{{"x":3.25,"y":-1.5,"heading":0.785}},"sensor":{{"x":0.1,"y":0,"theta":0}},)"
                     R"("angle_min":-2.356,"angle_increment":{:.6f},"ranges":[{}],"max_range":4.0}})",
                     4.712 / n, ranges);
}

std::string v2_points(int n) {
  std::string points;
  for (int i = 0; i < n; ++i)
    points += fmt::format("{}[{:.3f},{:.3f}]", i > 0 ? "," : "", 1.0 + 0.01 * i, -2.0 + 0.02 * i);
  return fmt::format(R"({{"pose":{{"x":1,"y":2,"heading":0.5}},"points":[{}]}})", points);
}

void BM_ParseTopic(benchmark::State& state) {
  ParsedTopic parsed;
  for (auto _ : state) {
    benchmark::DoNotOptimize(parse_topic("v2/robot/robot-017/scan", parsed).is_ok());
    benchmark::DoNotOptimize(parsed);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ParseTopic);

void BM_DecodeV1(benchmark::State& state) {
  const auto payload = v1_payload(static_cast<int>(state.range(0)));
  const CodecLimits limits;
  DecodedObservation out;
  for (auto _ : state) {
    benchmark::DoNotOptimize(decode_v1(payload, limits, out).is_ok());
    benchmark::DoNotOptimize(out.hits.data());
  }
  state.SetItemsProcessed(state.iterations());
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(payload.size()));
}
BENCHMARK(BM_DecodeV1)->Arg(0)->Arg(16)->Arg(360)->Arg(4096);

void BM_EncodeV1Waypoint(benchmark::State& state) {
  std::array<std::uint8_t, kV1PairBytes> out{};
  Point waypoint{1.0, -2.5};
  for (auto _ : state) {
    benchmark::DoNotOptimize(waypoint);
    benchmark::DoNotOptimize(encode_v1_waypoint(waypoint, 100.0, out).is_ok());
    benchmark::DoNotOptimize(out);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_EncodeV1Waypoint);

void BM_DecodeV2Pose(benchmark::State& state) {
  const std::string payload = R"({"x":3.25,"y":-1.5,"heading":0.785})";
  DecodedObservation out;
  for (auto _ : state) benchmark::DoNotOptimize(decode_v2_pose(as_bytes(payload), {}, out).is_ok());
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DecodeV2Pose);

void BM_DecodeV2Status(benchmark::State& state) {
  const std::string payload = R"({"battery":0.82,"state":"exploring"})";
  DecodedStatus out;
  for (auto _ : state) benchmark::DoNotOptimize(decode_v2_status(as_bytes(payload), {}, out).is_ok());
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DecodeV2Status);

void BM_DecodeV2Points(benchmark::State& state) {
  const std::string payload = v2_points(static_cast<int>(state.range(0)));
  DecodedObservation out;
  for (auto _ : state) benchmark::DoNotOptimize(decode_v2_points(as_bytes(payload), {}, out).is_ok());
  state.SetItemsProcessed(state.iterations());
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(payload.size()));
}
BENCHMARK(BM_DecodeV2Points)->Arg(16)->Arg(360);

void BM_DecodeV2Scan(benchmark::State& state) {
  const std::string payload = v2_scan(static_cast<int>(state.range(0)));
  DecodedObservation out;
  for (auto _ : state) benchmark::DoNotOptimize(decode_v2_scan(as_bytes(payload), {}, out).is_ok());
  state.SetItemsProcessed(state.iterations());
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(payload.size()));
}
BENCHMARK(BM_DecodeV2Scan)->Arg(16)->Arg(360)->Arg(1024);

void BM_EncodeV2Path(benchmark::State& state) {
  std::vector<Point> path;
  for (int i = 0; i < state.range(0); ++i) path.push_back({0.25 * i, -0.125 * i});
  std::string out;
  for (auto _ : state) benchmark::DoNotOptimize(encode_v2_path(17, path, {}, out).is_ok());
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_EncodeV2Path)->Arg(32);

}  // namespace

BENCHMARK_MAIN();
