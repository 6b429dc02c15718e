#pragma once
// slam-simulator's flags as a plain struct with defaults, the CLI11 binding (each flag range-checked
// so a bad value exits 2 naming the flag), and the simulation configuration built from them.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

#include "common/core/result.hpp"
#include "common/core/service_options.hpp"
#include "protocol/codec_types.hpp"
#include "simulator/core/config.hpp"
#include "simulator/core/play_options.hpp"

namespace slam::sim {

// Vda5050: a VDA 5050 2.0 robot (manufacturer "slamfleet-sim", serialNumber its robot id), which
// reports its pose (no scans: the standard has none) and drives the fleet control's orders.
enum class RobotProtocol : uint8_t { V1, V2, Vda5050 };

struct SimOptions {
  ServiceOptions service;
  std::string world = "office";  // built-in name or file (see load_world)
  int robots = 3;                // spawned at random free poses at start
  int vda_robots =
      0;  // of those, the first this many speak VDA 5050 whatever `protocol` says (a mixed fleet)
  std::string protocol = "v1";                               // "v1", "v2" or "vda5050"
  double rate_hz = 10.0;                                     // reports per robot per second
  double noise = 0.01;                                       // range noise standard deviation, m
  double dropout = 0.0;                                      // probability a beam returns nothing
  double drift = 0.02;                                       // odometry drift, m per sqrt(m) driven
  double heading_drift = OdometryConfig{}.drift_per_radian;  // rad per sqrt(rad) turned
  std::string odom_frame = "world";                          // "world" or "start" (see OdomFrame)
  uint64_t seed = 1;
  std::string broker = "tcp://127.0.0.1:1883";
  bool random_walk = false;
  double speed = 1.0;           // simulated seconds per wall-clock second
  bool mqtt_multiplex = false;  // one MQTT client for every robot instead of one each
  std::string mqtt_password;    // each robot logs in as its id with it; empty: anonymous
  std::string tls_ca_file;      // PEM CA the broker must be signed by (ssl:// and mqtts:// brokers)
  double units_per_meter = 100.0;
  double truth_rate_hz = 5.0;  // SimGroundTruth publications per second
  int beams = 16;
  double max_range = 4.0;
  PlayOptions play;        // --play LOG: play recorded logs instead of simulating (log_player.hpp)
  std::string record_log;  // --record-log PREFIX: each robot's CARMEN log and relations (log_recorder.hpp)

  RobotProtocol robot_protocol() const {
    if (protocol == "vda5050") return RobotProtocol::Vda5050;
    return protocol == "v2" ? RobotProtocol::V2 : RobotProtocol::V1;
  }
};

void add_sim_options(CLI::App& app, SimOptions& options);

// The simulation parameters the flags describe; the error names the flag that makes them invalid.
Result<SimulationConfig> simulation_config(const SimOptions& options);

// Codec limits matching the flags (the v1 scale).
protocol::CodecLimits codec_limits(const SimOptions& options);

// Checks what single-flag ranges cannot (the broker URL scheme, combined simulation values).
Status validate(const SimOptions& options);

}  // namespace slam::sim
