// bench_pipeline: the whole system under fleet load on this machine. 1000 simulated robots
// (slam-simulator, v1, one multiplexed MQTT connection, 10 Hz, 9 beams: 10 points a message)
// drive through a generated 80 m x 80 m world of 8 m rooms; their messages go mosquitto ->
// slam-gateway -> slam-mapper, with slam-planner running on the map. Over a window it measures
//   - the sustained rate: messages sent by the simulator vs received by the gateway vs integrated
//     by the mapper, from the services' heartbeat counters over DDS (each service's own clock),
//   - whether queues grow: the mapper's backlog (gateway observations - mapper intake) at the
//     start and end of the window, every dropped counter, and after the window, with the fleet
//     paused, how long the queues take to drain and how many messages never arrive,
//   - CPU per process (/proc/<pid>/stat over the window) and of the whole machine,
//   - the robot-to-map delay: probe messages from one extra robot (pipeline_probe.hpp), timed from
//     publish to the first GridTiles patch showing the probe's cell occupied; p50/p99 over the window.
// It starts mosquitto (free port) and every service (leased DDS domain) itself and stops them.
// Run: build/bin/bench_pipeline --benchmark_format=json
//   SLAM_BENCH_PIPELINE_SECONDS=N (window, default 30), SLAM_BENCH_PIPELINE_ROBOTS=N (default 1000),
//   SLAM_BENCH_PIPELINE_GATEWAYS=N / SLAM_BENCH_PIPELINE_PLANNERS=N (instances sharing the work,
//   default 1), SLAM_BENCH_PIPELINE_BIN_DIR=DIR (the services of another build), SLAM_BENCH_PIPELINE_SLAM=off
//   SLAM_BENCH_PIPELINE_BRIDGE=1: slam-bridge runs too, with one Foxglove WebSocket client
//   subscribed to every channel (pipeline_bridge_client.hpp); its CPU is cpu_bridge_pct.
#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "common/core/clock.hpp"
#include "mqtt_test_client.hpp"
#include "pipeline_bridge_client.hpp"
#include "pipeline_probe.hpp"
#include "pipeline_rig.hpp"

namespace slam::bench {
namespace {

using namespace std::chrono_literals;

constexpr double kProbePeriodS = 0.15;  // ~200 probes in 30 s, a few in flight at a time
constexpr char kProbeTopic[] = "v1/robot/probe/adv";

// mosquitto's own count of messages it dropped (queue and in-flight limits), which no service can
// see: published every sys_interval (1 s in the test broker).
constexpr char kBrokerDroppedTopic[] = "$SYS/broker/publish/messages/dropped";

// A connection to the bench's broker.
Result<std::unique_ptr<testkit::MqttTestClient>> connect_client(int port, const std::string& client_id) {
  try {
    auto client = std::make_unique<testkit::MqttTestClient>(port, client_id);
    if (const int rc = client->connect(); rc != 0)
      return Error{fmt::format("{}: connect to port {} failed ({})", client_id, port, rc)};
    return client;
  } catch (const std::exception& e) {
    return Error{e.what()};
  }
}

// The broker's latest dropped count as `sys` (subscribed to it) received it; -1 before the first one.
int64_t broker_dropped(const testkit::MqttTestClient& sys) {
  const auto message = sys.last(kBrokerDroppedTopic);
  if (!message) return -1;
  char* end = nullptr;
  const long long value = std::strtoll(message->payload.c_str(), &end, 10);
  return end == message->payload.c_str() ? -1 : value;
}

// Everything sampled at one end of the window.
struct WindowEdge {
  int64_t monotonic_ns = 0;
  std::map<std::string, CounterSample> counters;  // by service, summed over its instances
  std::map<std::string, std::map<std::string, CounterSample>> instances;  // by service, then instance
  std::map<std::string, double> cpu_s;   // by process, plus "bench" (this process)
  std::map<std::string, int64_t> waits;  // voluntary context switches, by process
  MachineCpu machine;
  uint64_t patch_bytes = 0;            // GridTiles bytes (CDR) this process received so far
  uint64_t patch_cells = 0;            // cells in those tiles (the raw size, before run-length coding)
  int64_t broker_dropped = -1;         // mosquitto's dropped count so far (-1: not reported yet)
  BridgeClient::Totals bridge_client;  // what the bench's Foxglove client received so far
};

WindowEdge sample_edge(const PipelineRig& rig, const ProbeSet& probes,
                       const testkit::MqttTestClient& broker_sys, const BridgeClient* bridge_client) {
  WindowEdge e;
  if (bridge_client) {
    e.bridge_client = bridge_client->totals();
    e.counters["bridge"] = rig.latest("bridge");
  }
  e.broker_dropped = broker_dropped(broker_sys);
  e.patch_bytes = probes.patch_bytes();
  e.patch_cells = probes.patch_cells();
  e.monotonic_ns = monotonic_ns();
  for (const char* service : {"gateway", "mapper", "planner", "simulator"}) {
    e.counters[service] = rig.latest(service);
    e.instances[service] = rig.instances(service);
  }
  for (const auto& [name, pid] : rig.processes()) {
    e.cpu_s[name] = process_cpu_s(pid);
    e.waits[name] = process_waits(pid);
  }
  e.cpu_s["bench"] = process_cpu_s(::getpid());
  e.machine = machine_cpu();
  return e;
}

// Observations the mapper took in so far: integrated, rejected, dropped at its intake, or held by
// pose correction until their keyframe is matched (slam_held: taken in, not yet in the grid).
int64_t mapper_taken_in(const CounterSample& mapper) {
  return mapper.get("observations") + mapper.get("rejected") + mapper.get("dropped") +
         mapper.get("slam_held");
}

// Observations the gateway published that the mapper has not taken in yet, with the gateway's
// count moved to the mapper heartbeat's time at the gateway's rate (heartbeats are not aligned),
// less `startup_gap`: what the gateway published before the mapper's reader matched it, which the
// counters (totals since start) carry forever but no queue holds.
double mapper_backlog(const CounterSample& gateway, const CounterSample& mapper, double gateway_rate,
                      double startup_gap) {
  const double gateway_at_mapper_time =
      static_cast<double>(gateway.get("observations")) +
      gateway_rate * static_cast<double>(mapper.stamp_ns - gateway.stamp_ns) / 1e9;
  return gateway_at_mapper_time - static_cast<double>(mapper_taken_in(mapper)) - startup_gap;
}

// With the fleet paused, lets every queue drain, which tells messages still queued from messages
// lost. Ends when the gateway has every message the simulator (and the probe) sent and the mapper
// every observation the gateway published, or when neither count moved for kStallS. The gaps
// are totals since the processes started; the bench drains once before the window too and
// subtracts, so what was lost while the services were still matching is not counted.
struct Drain {
  double seconds = 0.0;         // from the pause until both counts matched or stopped moving (>= 1.5)
  double gateway_gap = 0.0;     // sent by the simulator or the probe, not received by the gateway
  double mapper_gap = 0.0;      // published by the gateway, not taken in by the mapper
  double mapper_counted = 0.0;  // of those: batches counted lost (SAMPLE_LOST) + observations dropped
  bool settled = false;         // false: still moving at the timeout, so the gaps are still queued in part
};

Drain drain(PipelineRig& rig, size_t probes_sent, int64_t paused_at_ns, std::chrono::seconds timeout) {
  constexpr double kStallS = 3.0;
  const int64_t t0 = paused_at_ns;
  std::this_thread::sleep_for(1500ms);  // the simulator's last reports appear in its next heartbeat
  int64_t last_change = monotonic_ns();
  int64_t last_in = -1, last_intake = -1;
  Drain d;
  while (true) {
    const CounterSample sim = rig.latest("simulator"), gateway = rig.latest("gateway"),
                        mapper = rig.latest("mapper");
    const int64_t sent = sim.get("reports_sent") + static_cast<int64_t>(probes_sent);
    const int64_t in = gateway.get("messages_in");
    const int64_t intake = mapper_taken_in(mapper);
    const int64_t now = monotonic_ns();
    if (in != last_in || intake != last_intake) last_change = now;
    last_in = in;
    last_intake = intake;
    d.gateway_gap = static_cast<double>(sent - in);
    d.mapper_gap = static_cast<double>(gateway.get("observations") - intake);
    d.mapper_counted = static_cast<double>(mapper.get("observation_batches_lost") + mapper.get("dropped"));
    const bool complete = d.gateway_gap <= 0 && d.mapper_gap <= 0;
    const bool stalled = static_cast<double>(now - last_change) / 1e9 >= kStallS;
    if (complete || stalled || now - t0 > std::chrono::nanoseconds(timeout).count()) {
      d.settled = complete || stalled;
      d.seconds = static_cast<double>((complete ? now : last_change) - t0) / 1e9;
      return d;
    }
    std::this_thread::sleep_for(200ms);
  }
}

bool g_failed = false;  // main's exit code: an error in the run fails the program, not only its JSON

void fail(benchmark::State& state, const std::string& message) {
  g_failed = true;
  state.SkipWithError(message.c_str());
}

// The bridge's figures (SLAM_BENCH_PIPELINE_BRIDGE=1): its samples taken from DDS, what its one
// client received, and what it dropped for that client. Its CPU is reported with the others.
void report_bridge(benchmark::State& state, WindowEdge& start, WindowEdge& end, double window_s) {
  auto& c = state.counters;
  const BridgeClient::Totals &from = start.bridge_client, &to = end.bridge_client;
  c["bridge_samples_per_s"] =
      rate_between(start.counters["bridge"], end.counters["bridge"], "samples_received");
  c["bridge_dropped"] = static_cast<double>(end.counters["bridge"].get("messages_dropped") -
                                            start.counters["bridge"].get("messages_dropped"));
  c["bridge_client_channels"] = to.channels;
  c["bridge_client_msgs_per_s"] = static_cast<double>(to.messages - from.messages) / window_s;
  c["bridge_client_mb_per_s"] = static_cast<double>(to.bytes - from.bytes) / 1e6 / window_s;
  std::fprintf(stderr,
               "  bridge: %.1f %% of one core; took %.0f DDS samples/s; its client (%u channels%s) received "
               "%.1f messages/s, %.2f MB/s; %.0f messages dropped for it\n",
               c["cpu_bridge_pct"].value, c["bridge_samples_per_s"].value, to.channels,
               to.open ? "" : ", connection closed", c["bridge_client_msgs_per_s"].value,
               c["bridge_client_mb_per_s"].value, c["bridge_dropped"].value);
}

// Window figures as benchmark counters (JSON) and as a few readable lines on stderr.
void report(benchmark::State& state, const PipelineSettings& settings, WindowEdge& start, WindowEdge& end,
            const ProbeSet::Summary& probe, const Drain& before, const Drain& drained) {
  const double window_s = static_cast<double>(end.monotonic_ns - start.monotonic_ns) / 1e9;
  // Summed over a service's instances, each over its own heartbeats' interval.
  auto rate = [&](const char* service, const char* counter) {
    double total = 0.0;
    for (const auto& [instance, last] : end.instances[service]) {
      const auto first = start.instances[service].find(instance);
      if (first != start.instances[service].end()) total += rate_between(first->second, last, counter);
    }
    return total;
  };
  auto delta = [&](const char* service, const char* counter) {
    return static_cast<double>(end.counters[service].get(counter) - start.counters[service].get(counter));
  };
  const double sent = rate("simulator", "reports_sent");
  const double gateway_in = rate("gateway", "messages_in");
  const double gateway_obs = rate("gateway", "observations");
  const double mapper_obs = rate("mapper", "observations");
  auto& c = state.counters;
  c["robots"] = settings.robots;
  c["gateways"] = settings.gateways;
  c["planners"] = settings.planners;
  c["window_s"] = window_s;
  c["sim_sent_per_s"] = sent;
  c["gateway_in_per_s"] = gateway_in;
  c["gateway_states_per_s"] = rate("gateway", "robot_states");
  c["mapper_obs_per_s"] = mapper_obs;
  c["gateway_over_sim"] = sent > 0 ? gateway_in / sent : 0.0;
  c["mapper_over_gateway"] = gateway_obs > 0 ? mapper_obs / gateway_obs : 0.0;
  c["points_per_obs"] =
      delta("mapper", "observations") > 0 ? delta("mapper", "points") / delta("mapper", "observations") : 0.0;
  c["mapper_backlog_start"] =
      mapper_backlog(start.counters["gateway"], start.counters["mapper"], gateway_obs, before.mapper_gap);
  c["mapper_backlog_end"] =
      mapper_backlog(end.counters["gateway"], end.counters["mapper"], gateway_obs, before.mapper_gap);
  c["mapper_startup_gap"] = before.mapper_gap;
  // Of the backlog, what pose correction holds back at the window's end (observations wait, unrendered,
  // until their keyframe is matched): in open keyframes is by design (a keyframe closes after 0.4 m of
  // travel), in closed ones is matching not keeping up. Counted once a second by the mapper.
  c["mapper_held_open_end"] = static_cast<double>(end.counters["mapper"].get("slam_held_open"));
  c["mapper_held_matching_end"] = static_cast<double>(end.counters["mapper"].get("slam_held") -
                                                      end.counters["mapper"].get("slam_held_open"));
  c["slam_keyframes_per_s"] = rate("mapper", "slam_keyframes");
  c["slam_placed_by_odometry"] = delta("mapper", "slam_placed_by_odometry");
  c["mapper_dropped"] = delta("mapper", "dropped");
  c["mapper_dds_lost"] = delta("mapper", "observation_batches_lost");
  // -1 when mosquitto never reported: unknown, not zero.
  c["broker_dropped"] = start.broker_dropped >= 0 && end.broker_dropped >= 0
                            ? static_cast<double>(end.broker_dropped - start.broker_dropped)
                            : -1.0;
  c["mapper_rejected"] = delta("mapper", "rejected");
  c["gateway_rejected"] = static_cast<double>(end.counters["gateway"].sum_prefixed("rejected_") -
                                              start.counters["gateway"].sum_prefixed("rejected_"));
  c["gateway_write_failures"] = delta("gateway", "write_failures") + delta("gateway", "publish_failures");
  c["sim_reports_dropped"] = delta("simulator", "reports_dropped");
  c["sim_loop_overruns"] = delta("simulator", "loop_overruns");
  c["mapper_patches_per_s"] = rate("mapper", "patches");
  c["planner_patches_applied_per_s"] = rate("planner", "patches_applied");
  c["planner_patches_skipped"] = delta("planner", "patches_skipped");
  c["patch_mb_per_s"] = static_cast<double>(end.patch_bytes - start.patch_bytes) / 1e6 / window_s;
  c["patch_cells_mb_per_s"] = static_cast<double>(end.patch_cells - start.patch_cells) / 1e6 / window_s;
  c["drain_s"] = drained.seconds;
  c["drain_settled"] = drained.settled ? 1.0 : 0.0;
  c["lost_to_gateway"] = drained.gateway_gap - before.gateway_gap;
  c["lost_to_mapper"] = drained.mapper_gap - before.mapper_gap;
  // Shedding is visible when the mapper's own counters account for what it lost.
  c["lost_to_mapper_counted"] = drained.mapper_counted - before.mapper_counted;
  // The whole pipeline's CPU per robot message: every service process (not this bench), summed,
  // per message the gateways took in (the same as sent when the pipeline keeps up; on an
  // overloaded machine the messages still queued at the broker cost nothing yet).
  double ours = 0.0, services = 0.0;
  std::map<std::string, double> by_service;  // gateway2 counted under gateway
  for (const auto& [name, cpu] : end.cpu_s) {
    const double share = 100.0 * (cpu - start.cpu_s[name]) / window_s;
    c["cpu_" + name + "_pct"] = share;
    ours += share;
    if (name == "bench") continue;
    services += share;
    by_service[PipelineRig::service_of(name)] += share;
  }
  double waits = 0.0;
  for (const auto& [name, count] : end.waits) {
    const double n = static_cast<double>(count - start.waits[name]);
    c["waits_" + name + "_per_s"] = n / window_s;
    waits += n;
  }
  c["cpu_services_pct"] = services;
  c["waits_per_message"] = gateway_in > 0 ? waits / window_s / gateway_in : 0.0;
  c["cpu_us_per_message"] = gateway_in > 0 ? services / 100.0 / gateway_in * 1e6 : 0.0;
  std::string per_service;
  for (const char* service : {"mosquitto", "gateway", "mapper", "planner", "simulator", "bridge"})
    if (by_service.contains(service)) per_service += fmt::format("{} {:.0f}, ", service, by_service[service]);
  // Each gateway's share of the messages, and the planners' CPU one by one, when there are several.
  std::string shares;
  if (settings.gateways > 1 || settings.planners > 1) {
    shares = "  instances:";
    for (const auto& [instance, last] : end.instances["gateway"]) {
      const auto first = start.instances["gateway"].find(instance);
      if (first != start.instances["gateway"].end())
        shares += fmt::format(" gateway {} {:.0f} msg/s;", instance,
                              rate_between(first->second, last, "messages_in"));
    }
    for (const auto& [name, cpu] : end.cpu_s) {
      const std::string service = PipelineRig::service_of(name);
      if ((service == "gateway" && settings.gateways > 1) || (service == "planner" && settings.planners > 1))
        shares += fmt::format(" {} {:.0f} % CPU;", name, c["cpu_" + name + "_pct"].value);
    }
    shares += "\n";
  }
  const double machine_total = end.machine.total_s - start.machine.total_s;
  const double machine_busy =
      machine_total > 0 ? (end.machine.busy_s - start.machine.busy_s) / machine_total : 0.0;
  c["cpu_machine_busy_pct"] = 100.0 * machine_busy;                              // of all cores
  c["cpu_others_pct"] = 100.0 * machine_busy * machine_total / window_s - ours;  // of one core
  c["probes_sent"] = static_cast<double>(probe.sent);
  c["probes_seen"] = static_cast<double>(probe.seen);
  c["delay_p50_ms"] = probe.p50_ms;
  c["delay_p99_ms"] = probe.p99_ms;
  c["delay_max_ms"] = probe.max_ms;

  auto v = [&](const char* name) { return c[name].value; };
  std::fprintf(
      stderr,
      "bench_pipeline: %d robots, %d gateway(s), %d planner(s), %.1f s window\n"
      "  rate: simulator sent %.0f msg/s, gateway received %.0f msg/s (%.3f), mapper integrated %.0f obs/s "
      "(%.3f of the gateway's), %.1f points per observation; gateway RobotState %.0f/s\n"
      "  queues: mapper backlog %.0f -> %.0f observations (%.0f published before the mapper matched left "
      "out); dropped: mapper %.0f, simulator %.0f, "
      "broker %.0f; batches lost by DDS before the mapper %.0f; simulator loop overruns %.0f\n"
      "  pose correction at the end: %.0f observations in open keyframes (by design), %.0f in closed "
      "keyframes "
      "not yet matched; %.0f keyframes/s, %.0f placed by odometry alone in the window\n"
      "  after pausing the fleet: %s %.1f s; %s: %.0f at the gateway, %.0f at the mapper (%.0f of them "
      "counted lost or dropped by the mapper)\n"
      "  map stream: %.1f patches/s, %.2f MB/s of patches to each reader (%.2f MB/s of tile cells uncoded)\n"
      "  delay robot message -> patch: p50 %.0f ms, p99 %.0f ms, max %.0f ms (%zu of %zu probes seen)\n"
      "  CPU %% of one core: %sbench %.0f; other processes %.0f; machine %.0f %% busy\n"
      "  whole pipeline (services summed): %.0f %% of a core, %.1f us CPU and %.2f thread waits per robot "
      "message\n%s",
      settings.robots, settings.gateways, settings.planners, window_s, sent, gateway_in,
      v("gateway_over_sim"), mapper_obs, v("mapper_over_gateway"), v("points_per_obs"),
      v("gateway_states_per_s"), v("mapper_backlog_start"), v("mapper_backlog_end"), v("mapper_startup_gap"),
      v("mapper_dropped"), v("sim_reports_dropped"), v("broker_dropped"), v("mapper_dds_lost"),
      v("sim_loop_overruns"), v("mapper_held_open_end"), v("mapper_held_matching_end"),
      v("slam_keyframes_per_s"), v("slam_placed_by_odometry"),
      drained.settled ? "queues drained in" : "still draining after", drained.seconds,
      drained.settled ? "never arrived" : "not arrived yet", v("lost_to_gateway"), v("lost_to_mapper"),
      v("lost_to_mapper_counted"), v("mapper_patches_per_s"), v("patch_mb_per_s"), v("patch_cells_mb_per_s"),
      probe.p50_ms, probe.p99_ms, probe.max_ms, probe.seen, probe.sent, per_service.c_str(),
      v("cpu_bench_pct"), v("cpu_others_pct"), v("cpu_machine_busy_pct"), services, v("cpu_us_per_message"),
      v("waits_per_message"), shares.c_str());
  if (end.counters.contains("bridge")) report_bridge(state, start, end, window_s);
}

void BM_Pipeline(benchmark::State& state) {
  auto settings = pipeline_settings_from_env();
  if (!settings) return fail(state, settings.message());
  auto rig = PipelineRig::start(*settings);
  if (!rig) return fail(state, rig.message());
  ProbeSet probes(settings->grid, static_cast<size_t>(settings->seconds / kProbePeriodS));
  // Declared after `probes`, so the readers that call into it are destroyed first.
  auto snapshots = dds::make_reader((*rig)->participant(), dds::kGridSnapshot,
                                    [&](const GridSnapshot& s, const auto&) { probes.on_snapshot(s); });
  auto patches = dds::make_reader((*rig)->participant(), dds::kGridTiles,
                                  [&](const GridTiles& p, const auto&) { probes.on_patch(p); });
  if (!snapshots) return fail(state, snapshots.message());
  if (!patches) return fail(state, patches.message());
  auto probe_client = connect_client((*rig)->broker_port(), "bench-pipeline-probe");
  if (!probe_client) return fail(state, probe_client.message());
  auto broker_sys = connect_client((*rig)->broker_port(), "bench-pipeline-sys");
  if (!broker_sys) return fail(state, broker_sys.message());
  if (!(*broker_sys)->subscribe(kBrokerDroppedTopic, 0))
    return fail(state, "bench-pipeline-sys: subscribe failed");
  if (Status s = (*rig)->wait_until_running(120s); !s) return fail(state, s.message());
  std::unique_ptr<BridgeClient> bridge_client;
  if (settings->bridge) {
    auto client = BridgeClient::connect(static_cast<uint16_t>((*rig)->bridge_port()));
    if (!client) return fail(state, client.message());
    bridge_client = std::move(*client);
    if (!bridge_client->wait_subscribed(1, 10s))
      return fail(state, "the bench's Foxglove client got no channels from the bridge");
  }
  std::this_thread::sleep_for(std::chrono::duration<double>(settings->warmup_s));
  // What went missing while the services were still matching each other, so it is not counted.
  if (Status s = (*rig)->control_simulator(SIM_PAUSE); !s) return fail(state, s.message());
  const Drain before = drain(**rig, 0, monotonic_ns(), 60s);
  if (Status s = (*rig)->control_simulator(SIM_RESUME); !s) return fail(state, s.message());
  std::this_thread::sleep_for(3s);  // back to a steady rate

  WindowEdge start, end;
  ProbeSet::Summary probe;
  Drain drained;
  for (auto _ : state) {
    start = sample_edge(**rig, probes, **broker_sys, bridge_client.get());
    const int64_t window_ns = static_cast<int64_t>(settings->seconds * 1e9);
    for (size_t k = 0; k < probes.size(); ++k) {
      const int64_t due =
          start.monotonic_ns + static_cast<int64_t>(static_cast<double>(k) * kProbePeriodS * 1e9);
      if (due - start.monotonic_ns >= window_ns) break;
      if (const int64_t wait = due - monotonic_ns(); wait > 0)
        std::this_thread::sleep_for(std::chrono::nanoseconds(wait));
      probes.mark_sent(k, monotonic_ns());
      if (!(*probe_client)->publish(kProbeTopic, probes.payload(k), 0))  // QoS 0, as the robots publish
        return fail(state, "probe publish failed");
    }
    if (const int64_t rest = start.monotonic_ns + window_ns - monotonic_ns(); rest > 0)
      std::this_thread::sleep_for(std::chrono::nanoseconds(rest));
    end = sample_edge(**rig, probes, **broker_sys, bridge_client.get());
    if (Status s = (*rig)->control_simulator(SIM_PAUSE); !s) return fail(state, s.message());
    const int64_t paused_at = monotonic_ns();
    // Probes still in flight get 5 s more; unseen ones then count with their age.
    testkit::wait_until(
        [&] {
          auto p = probes.summary(monotonic_ns());
          return p.seen == p.sent;
        },
        5s, 50ms);
    probe = probes.summary(monotonic_ns());
    drained = drain(**rig, probe.sent, paused_at, 120s);
    if (Status s = (*rig)->check_running(); !s) return fail(state, s.message());
  }
  report(state, *settings, start, end, probe, before, drained);
}
BENCHMARK(BM_Pipeline)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace
}  // namespace slam::bench

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return slam::bench::g_failed ? 1 : 0;
}
