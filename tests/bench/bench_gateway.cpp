// bench_gateway: the gateway as robots and consumers see it. Starts its own mosquitto (free port)
// and slam-gateway (free DDS domain), then measures
//   BM_BrokerBaseline     mosquitto -> plain paho subscriber, loopback: the ceiling
//   BM_GatewayThroughput  MQTT -> gateway -> DDS reader, sustained (items_per_second), gateway RSS
//                         before and after (memory must stay flat)
//   BM_GatewayLatency     publish -> DDS sample at a fixed 10k msg/s: p50/p99, and the same for
//                         publish -> paho subscriber, so the gateway's added latency shows
// Throughput runs keep a window of messages in flight (published - received <= kWindow), so what
// is measured is the pipeline's sustained rate, with no message lost to a queue overflowing.
// Message count: SLAM_BENCH_GATEWAY_MESSAGES (default 1000000). The gateway runs with --batch-ms
// SLAM_BENCH_GATEWAY_BATCH_MS (default 0: every observation in a sample of its own, so (c) is the
// gateway's own latency; its default of 10 ms adds up to that much by design). The gateway is the
// build's slam-gateway, or SLAM_BENCH_GATEWAY_BIN (another build of it: before/after comparisons with
// one bench binary, runs interleaved). Run:
//   build/bin/bench_gateway --benchmark_format=json
#include <MQTTAsync.h>
#include <benchmark/benchmark.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "common/core/clock.hpp"
#include "common/fastdds/fast_topics.hpp"
#include "observation_batches.hpp"
#include "process_group.hpp"

namespace {

using namespace std::chrono_literals;

constexpr int64_t kWindow = 256;  // below the DDS stream history (1000): nothing is overwritten
constexpr char kBaselineTopic[] = "bench/baseline";  // the gateway does not subscribe this
constexpr char kThroughputTopic[] = "v1/robot/tp/adv";
constexpr char kLatencyTopic[] = "v1/robot/lat/adv";

std::string gateway_bin() {
  const char* env = std::getenv("SLAM_BENCH_GATEWAY_BIN");
  return env && *env ? env : SLAM_GATEWAY_BIN;
}

std::string batch_ms() {
  const char* env = std::getenv("SLAM_BENCH_GATEWAY_BATCH_MS");
  return env ? env : "0";
}

int64_t message_count() {
  const char* env = std::getenv("SLAM_BENCH_GATEWAY_MESSAGES");
  return env ? std::max<int64_t>(1000, std::atoll(env)) : 1'000'000;
}

// v1 adv payload: position = message index in two int16 halves, plus one obstacle point.
std::array<uint8_t, 8> payload_for(int64_t index) {
  const auto lo = static_cast<uint16_t>(index & 0x7fff);
  const auto hi = static_cast<uint16_t>((index >> 15) & 0x7fff);
  return {static_cast<uint8_t>(lo & 0xff),
          static_cast<uint8_t>(lo >> 8),
          static_cast<uint8_t>(hi & 0xff),
          static_cast<uint8_t>(hi >> 8),
          0x10,
          0x00,
          0x20,
          0x00};
}
int64_t index_from_bytes(const uint8_t* p) {
  return static_cast<int64_t>(p[0] | (p[1] << 8)) | (static_cast<int64_t>(p[2] | (p[3] << 8)) << 15);
}
int64_t index_from_metres(double x, double y) {  // inverse of the gateway's value / 100
  return static_cast<int64_t>(std::lround(x * 100.0)) | (static_cast<int64_t>(std::lround(y * 100.0)) << 15);
}

int64_t rss_kb(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string key;
  while (status >> key) {
    if (key == "VmRSS:") {
      int64_t kb = 0;
      status >> kb;
      return kb;
    }
    status.ignore(4096, '\n');
  }
  return -1;
}

// Latency samples: send time per index, and receive - send per index once it arrives.
struct LatencyLog {
  void reset(size_t n) {
    sent_ns.assign(n, 0);
    latency_ns.assign(n, -1);
  }
  void received(int64_t index, int64_t now) {
    if (index < 0 || static_cast<size_t>(index) >= sent_ns.size()) return;
    const int64_t sent = sent_ns[static_cast<size_t>(index)];
    if (sent > 0) latency_ns[static_cast<size_t>(index)] = now - sent;
  }
  // p in [0, 1] over the samples that arrived, in microseconds.
  double percentile_us(double p) const {
    std::vector<int64_t> got;
    for (int64_t l : latency_ns)
      if (l >= 0) got.push_back(l);
    if (got.empty()) return -1.0;
    const size_t k = std::min(got.size() - 1, static_cast<size_t>(p * static_cast<double>(got.size())));
    std::nth_element(got.begin(), got.begin() + static_cast<std::ptrdiff_t>(k), got.end());
    return static_cast<double>(got[k]) / 1000.0;
  }
  size_t arrived() const {
    return static_cast<size_t>(
        std::count_if(latency_ns.begin(), latency_ns.end(), [](int64_t l) { return l >= 0; }));
  }
  std::vector<int64_t> sent_ns;  // written by the publishing thread before the message goes out
  std::vector<int64_t> latency_ns;
};

// One MQTTAsync client, used as publisher or as the baseline subscriber.
class PahoClient {
 public:
  using OnMessage = void (*)(void*, const uint8_t*, int);
  PahoClient(int port, const char* id, OnMessage on_message = nullptr, void* context = nullptr)
      : on_message_(on_message), context_(context) {
    const std::string url = "tcp://127.0.0.1:" + std::to_string(port);
    if (MQTTAsync_create(&handle_, url.c_str(), id, MQTTCLIENT_PERSISTENCE_NONE, nullptr) !=
        MQTTASYNC_SUCCESS)
      throw std::runtime_error("MQTTAsync_create failed");
    MQTTAsync_setCallbacks(handle_, this, nullptr, &PahoClient::arrived, nullptr);
    MQTTAsync_connectOptions options = MQTTAsync_connectOptions_initializer;
    options.cleansession = 1;
    options.onSuccess = [](void* c, MQTTAsync_successData*) {
      static_cast<PahoClient*>(c)->ready_.store(true);
    };
    options.context = this;
    if (MQTTAsync_connect(handle_, &options) != MQTTASYNC_SUCCESS)
      throw std::runtime_error("MQTTAsync_connect failed");
    wait([&] { return ready_.load(); }, "connect");
  }
  ~PahoClient() {
    MQTTAsync_disconnectOptions options = MQTTAsync_disconnectOptions_initializer;
    MQTTAsync_disconnect(handle_, &options);
    std::this_thread::sleep_for(50ms);
    MQTTAsync_destroy(&handle_);
  }
  void subscribe(const char* filter) {
    subscribed_.store(false);
    MQTTAsync_responseOptions options = MQTTAsync_responseOptions_initializer;
    options.onSuccess = [](void* c, MQTTAsync_successData*) {
      static_cast<PahoClient*>(c)->subscribed_.store(true);
    };
    options.context = this;
    MQTTAsync_subscribe(handle_, filter, 0, &options);
    wait([&] { return subscribed_.load(); }, "subscribe");
  }
  void publish(const char* topic, const std::array<uint8_t, 8>& payload) {
    MQTTAsync_message message = MQTTAsync_message_initializer;
    message.payload = const_cast<uint8_t*>(payload.data());
    message.payloadlen = static_cast<int>(payload.size());
    message.qos = 0;
    MQTTAsync_responseOptions options = MQTTAsync_responseOptions_initializer;
    while (MQTTAsync_sendMessage(handle_, topic, &message, &options) != MQTTASYNC_SUCCESS)
      std::this_thread::yield();
  }

 private:
  template <class Pred>
  static void wait(Pred pred, const char* what) {
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    while (!pred()) {
      if (std::chrono::steady_clock::now() > deadline)
        throw std::runtime_error(std::string("MQTT ") + what + " timed out");
      std::this_thread::sleep_for(5ms);
    }
  }
  static int arrived(void* context, char* topic, int, MQTTAsync_message* message) {
    auto* self = static_cast<PahoClient*>(context);
    if (self->on_message_)
      self->on_message_(self->context_, static_cast<const uint8_t*>(message->payload), message->payloadlen);
    MQTTAsync_freeMessage(&message);
    MQTTAsync_free(topic);
    return 1;
  }

  MQTTAsync handle_ = nullptr;
  OnMessage on_message_;
  void* context_;
  std::atomic<bool> ready_{false};
  std::atomic<bool> subscribed_{false};
};

// Broker, gateway, DDS reader and clients, shared by every benchmark in this process.
class Rig {
 public:
  static Rig& get() {
    static Rig rig;
    return rig;
  }

  std::atomic<int64_t> baseline_received{0};
  std::atomic<int64_t> gateway_received{0};
  std::atomic<bool> measure_latency{false};
  LatencyLog baseline_latency;
  LatencyLog gateway_latency;
  pid_t gateway_pid() const { return gateway_pid_; }
  PahoClient& publisher() { return *publisher_; }

 private:
  Rig() {
    port_ = group_.start_mosquitto();
    group_.start("gateway", slam::testkit::with_dds_identity(
                                "gateway", {gateway_bin(), "--domain", std::to_string(domain_.id()),
                                            "--broker", "tcp://127.0.0.1:" + std::to_string(port_),
                                            "--batch-ms", batch_ms(), "--log-level", "warn"}));
    gateway_pid_ = group_.pid("gateway");
    auto participant = slam::dds::Participant::create(domain_.id(), "bench-gateway");
    if (!participant) throw std::runtime_error(participant.message());
    participant_ = std::move(*participant);
    reader_ = slam::testkit::make_observation_reader(
        *participant_, [this](const slam::RobotObservation& o) { observed(o); });
    auto subscriptions = slam::dds::make_reader(*participant_, slam::dds::kMqttSubscriptions,
                                                [this](const slam::MqttSubscriptions& s, const auto&) {
                                                  if (s.connected()) gateway_connected_.store(true);
                                                });
    if (!subscriptions) throw std::runtime_error(subscriptions.message());
    subscriptions_ = std::move(*subscriptions);
    if (!slam::testkit::wait_until(
            [&] { return gateway_connected_.load() && reader_->matched_writers() > 0; }, 30s)) {
      throw std::runtime_error("slam-gateway did not come up:\n" + group_.log("gateway"));
    }
    subscriber_ = std::make_unique<PahoClient>(port_, "bench-subscriber", &Rig::baseline_message, this);
    subscriber_->subscribe(kBaselineTopic);
    publisher_ = std::make_unique<PahoClient>(port_, "bench-publisher");
  }

  static void baseline_message(void* context, const uint8_t* payload, int size) {
    auto* self = static_cast<Rig*>(context);
    if (self->measure_latency.load(std::memory_order_relaxed) && size >= 4) {
      self->baseline_latency.received(index_from_bytes(payload), slam::monotonic_ns());
    }
    self->baseline_received.fetch_add(1, std::memory_order_release);
    self->baseline_received.notify_all();
  }
  void observed(const slam::RobotObservation& o) {
    if (measure_latency.load(std::memory_order_relaxed) && o.robot_id() == std::string("lat")) {
      gateway_latency.received(index_from_metres(o.pose().x(), o.pose().y()), slam::monotonic_ns());
    }
    gateway_received.fetch_add(1, std::memory_order_release);
    gateway_received.notify_all();
  }

  slam::testkit::DomainLease domain_;
  slam::testkit::ProcessGroup group_;
  int port_ = 0;
  pid_t gateway_pid_ = -1;
  std::atomic<bool> gateway_connected_{false};
  std::unique_ptr<slam::dds::Participant> participant_;
  std::unique_ptr<slam::dds::Reader<slam::RobotObservationBatch>> reader_;
  std::unique_ptr<slam::dds::Reader<slam::MqttSubscriptions>> subscriptions_;
  std::unique_ptr<PahoClient> subscriber_;
  std::unique_ptr<PahoClient> publisher_;
};

// Publishes `n` messages keeping at most kWindow in flight; returns when all arrived (or timeout).
bool pump(const char* topic, int64_t n, std::atomic<int64_t>& received) {
  Rig& rig = Rig::get();
  const int64_t start = received.load();
  for (int64_t i = 0; i < n; ++i) {
    // Block (not spin: two cores are shared with the broker and the gateway) while the window is full.
    for (int64_t r = received.load(std::memory_order_acquire); i - (r - start) >= kWindow;
         r = received.load(std::memory_order_acquire)) {
      received.wait(r, std::memory_order_acquire);
    }
    rig.publisher().publish(topic, payload_for(i));
  }
  return slam::testkit::wait_until([&] { return received.load() - start >= n; }, 30s, 1ms);
}

void BM_BrokerBaseline(benchmark::State& state) {
  Rig& rig = Rig::get();
  const int64_t n = message_count();
  for (auto _ : state) {
    if (!pump(kBaselineTopic, n, rig.baseline_received)) state.SkipWithError("baseline messages lost");
  }
  state.SetItemsProcessed(state.iterations() * n);
}

void BM_GatewayThroughput(benchmark::State& state) {
  Rig& rig = Rig::get();
  const int64_t n = message_count();
  pump(kThroughputTopic, 1000, rig.gateway_received);  // warm-up: first-seen robot, buffers sized
  const int64_t rss_before = rss_kb(rig.gateway_pid());
  for (auto _ : state) {
    if (!pump(kThroughputTopic, n, rig.gateway_received)) state.SkipWithError("gateway messages lost");
  }
  const int64_t rss_after = rss_kb(rig.gateway_pid());
  state.SetItemsProcessed(state.iterations() * n);
  state.counters["gateway_rss_before_kb"] = static_cast<double>(rss_before);
  state.counters["gateway_rss_after_kb"] = static_cast<double>(rss_after);
  state.counters["gateway_rss_growth_kb"] = static_cast<double>(rss_after - rss_before);
}

// Publishes n messages at `rate` per second on `topic`, stamping each in `log`.
void paced(const char* topic, int64_t n, double rate, LatencyLog& log, std::atomic<int64_t>& received) {
  Rig& rig = Rig::get();
  log.reset(static_cast<size_t>(n));
  const int64_t start_count = received.load();
  const int64_t period_ns = static_cast<int64_t>(1e9 / rate);
  const int64_t t0 = slam::monotonic_ns();
  for (int64_t i = 0; i < n; ++i) {
    // Sleep, not spin, until due (timer slack is set to 1 ns in main, so sleeps are precise).
    const int64_t due = t0 + i * period_ns;
    const int64_t wait = due - slam::monotonic_ns();
    if (wait > 0) std::this_thread::sleep_for(std::chrono::nanoseconds(wait));
    log.sent_ns[static_cast<size_t>(i)] = slam::monotonic_ns();
    rig.publisher().publish(topic, payload_for(i));
  }
  slam::testkit::wait_until([&] { return received.load() - start_count >= n; }, 10s, 1ms);
}

void BM_GatewayLatency(benchmark::State& state) {
  Rig& rig = Rig::get();
  constexpr double kRate = 10'000.0;
  const int64_t n = std::min<int64_t>(message_count(), 100'000);
  pump(kLatencyTopic, 1000, rig.gateway_received);  // warm-up
  for (auto _ : state) {
    rig.measure_latency.store(true);
    paced(kBaselineTopic, n, kRate, rig.baseline_latency, rig.baseline_received);
    paced(kLatencyTopic, n, kRate, rig.gateway_latency, rig.gateway_received);
    rig.measure_latency.store(false);
  }
  const double p50 = rig.gateway_latency.percentile_us(0.50);
  const double p99 = rig.gateway_latency.percentile_us(0.99);
  const double b50 = rig.baseline_latency.percentile_us(0.50);
  const double b99 = rig.baseline_latency.percentile_us(0.99);
  state.counters["rate_msg_per_s"] = kRate;
  state.counters["p50_us"] = p50;
  state.counters["p99_us"] = p99;
  state.counters["broker_p50_us"] = b50;
  state.counters["broker_p99_us"] = b99;
  state.counters["added_p50_us"] = p50 - b50;
  state.counters["added_p99_us"] = p99 - b99;
  state.counters["lost"] = static_cast<double>(static_cast<size_t>(n) - rig.gateway_latency.arrived());
  state.SetItemsProcessed(2 * n);
}

BENCHMARK(BM_BrokerBaseline)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_GatewayThroughput)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_GatewayLatency)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

// No Fast DDS XML profile here: the bench's participant and the gateway it starts get the services'
// own transport (dds::Participant: UDPv4 only, 4 MB socket buffers), the one deployments run. A
// profile given through FASTRTPS_DEFAULT_PROFILES_FILE replaces it: the one this bench once wrote
// for larger buffers left Fast DDS's shared-memory transport in use, a path no service takes.
int main(int argc, char** argv) {
  // Default timer slack (50 us) would stretch the 100 us pacing sleeps of the latency benchmark.
  ::prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
