#pragma once
// The whole system as one process group for bench_pipeline: mosquitto on a free port and
// slam-gateway, slam-mapper, slam-planner and slam-simulator on a leased DDS domain, a generated
// world, and what the bench reads from outside the processes: heartbeat counters over DDS and CPU
// time from /proc. Kept apart from the measurement so the benchmark reads as a list of steps.
#include <sys/types.h>

#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "common/core/result.hpp"
#include "common/fastdds/fast_topics.hpp"
#include "process_group.hpp"

namespace slam::bench {

// The mapper's grid, fixed at start so it never grows (a growth publishes snapshots instead of
// patches) and so the probe can put points in cells only it observes (see pipeline_probe.hpp).
struct GridLayout {
  double origin_x = -5.0;
  double origin_y = -5.0;
  double side_m = 90.0;
  double resolution = 0.05;
};

struct PipelineSettings {
  int robots = 1000;      // SLAM_BENCH_PIPELINE_ROBOTS
  double seconds = 30.0;  // SLAM_BENCH_PIPELINE_SECONDS: the measured window
  bool slam = true;       // SLAM_BENCH_PIPELINE_SLAM=off: the mapper runs with --slam off
  bool bridge = false;    // SLAM_BENCH_PIPELINE_BRIDGE=1: slam-bridge runs too (one client, see
                          // pipeline_bridge_client.hpp)
  int gateways = 1;       // SLAM_BENCH_PIPELINE_GATEWAYS: gateways sharing the robots
  int planners = 1;       // SLAM_BENCH_PIPELINE_PLANNERS: planners sharing the work
  // SLAM_BENCH_PIPELINE_BIN_DIR: the services' directory (default: this build's), so one bench
  // can measure the services of another build, e.g. before and after a change, interleaved.
  std::string bin_dir;
  double warmup_s = 5.0;       // after every robot reports, before the window
  int beams = 9;               // 9 obstacle points + the position = 10 v1 pairs per message
  double max_range_m = 12.0;   // longer than a room's diagonal: nearly every beam hits a wall
  double world_side_m = 80.0;  // square world of rooms with doors
  double room_m = 8.0;
  GridLayout grid;
};

// Settings with the environment overrides applied; an out-of-range value is an error naming it.
Result<PipelineSettings> pipeline_settings_from_env();

// The Java-format world text (sizes in cm): a square of `room_m` rooms, every internal wall with a
// 1.2 m door in the middle of each room side, so random walks reach everywhere.
std::string rooms_world_text(double side_m, double room_m);

// One service's counters as of one heartbeat.
struct CounterSample {
  int64_t stamp_ns = 0;
  std::map<std::string, int64_t> values;
  int64_t get(const std::string& name) const;
  int64_t sum_prefixed(const std::string& prefix) const;  // e.g. every "rejected_*" counter
};

// Change of a counter between two heartbeats, per second of the service's own clock.
double rate_between(const CounterSample& from, const CounterSample& to, const std::string& name);

// CPU seconds (user + system) a process used so far, all threads; negative if it is gone.
double process_cpu_s(pid_t pid);

// Times the threads of a process went to sleep waiting (voluntary context switches: a blocking
// receive, a futex wait), summed over its live threads; each is later paid for by a wake-up.
int64_t process_waits(pid_t pid);

// Busy and total CPU seconds of the whole machine so far (all cores), from /proc/stat.
struct MachineCpu {
  double busy_s = 0.0;
  double total_s = 0.0;
};
MachineCpu machine_cpu();

class PipelineRig {
 public:
  // Starts every process and the DDS readers. Errors name the process that did not come up.
  static Result<std::unique_ptr<PipelineRig>> start(const PipelineSettings& settings);

  // Waits until each service sent a heartbeat, the simulator runs every robot and the mapper
  // integrates observations.
  Status wait_until_running(std::chrono::seconds timeout);

  // Pauses (SIM_PAUSE) or resumes (SIM_RESUME) every simulated robot over DDS; heartbeats go on.
  Status control_simulator(SimCommandKind kind);

  // An error naming the first process that exited, with the end of its log.
  Status check_running();

  // Latest heartbeat counters of `service`, summed over its instances (several gateways or
  // planners), stamped with the newest of them; empty values when none arrived yet.
  CounterSample latest(const std::string& service) const;
  // Latest heartbeat counters of each instance of `service`, by instance id.
  std::map<std::string, CounterSample> instances(const std::string& service) const;

  int broker_port() const { return port_; }
  // The bridge's WebSocket port; 0 when the bridge does not run.
  int bridge_port() const { return bridge_port_; }
  dds::Participant& participant() { return *participant_; }
  // Name and pid of every process started: mosquitto, gateway (gateway2, ... when several),
  // mapper, planner (planner2, ...), simulator, and bridge when it runs.
  std::vector<std::pair<std::string, pid_t>> processes() const;
  // The service a process name belongs to: "gateway2" -> "gateway".
  static std::string service_of(const std::string& process);
  // Tail of a process's log, for error messages.
  std::string log_tail(const std::string& name) const;

 private:
  PipelineRig() = default;
  Status launch(const PipelineSettings& settings);

  testkit::DomainLease domain_;
  testkit::DomainLease sim_domain_;  // the simulator's own plain domain when DDS Security is on
  testkit::ProcessGroup group_;
  int port_ = 0;
  int bridge_port_ = 0;
  int robots_ = 0;
  int gateways_ = 1;
  int planners_ = 1;
  // Written by the listeners: declared before the readers so it outlives them (members are
  // destroyed in reverse order).
  mutable std::mutex mutex_;
  std::map<std::string, std::map<std::string, CounterSample>> latest_;  // by service, then instance
  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<dds::Participant> sim_participant_;  // DDS Security on: on sim_domain_, plain
  std::unique_ptr<dds::Reader<Heartbeat>> heartbeats_;
  std::unique_ptr<dds::Reader<Heartbeat>> sim_heartbeats_;
  std::unique_ptr<dds::Writer<SimControl>> sim_control_;
  uint64_t commands_sent_ = 0;
};

}  // namespace slam::bench
