// Flag definitions and checks for slam-simulator; defaults live in the struct.
#include "simulator/core/sim_options.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "simulator/core/sim_control.hpp"

namespace slam::sim {
namespace {

// Shortest step the simulation takes by default; faster report rates shorten it.
constexpr double kDefaultDt = 0.05;

}  // namespace

void add_sim_options(CLI::App& app, SimOptions& o) {
  add_service_options(app, o.service);
  app.add_option("--world", o.world,
                 "built-in world (empty, office, maze, track, rooms) or a world file (.txt, .yaml)")
      ->capture_default_str();
  app.add_option("--robots", o.robots, "robots spawned at random free poses at start")
      ->check(CLI::Range(0, static_cast<int>(kMaxFleet)))
      ->capture_default_str();
  app.add_option("--vda-robots", o.vda_robots,
                 "of the robots spawned at start, the first N speak VDA 5050, the others --protocol "
                 "(a mixed fleet in one world)")
      ->check(CLI::Range(0, static_cast<int>(kMaxFleet)))
      ->capture_default_str();
  app.add_option("--protocol", o.protocol,
                 "robot protocol: v1 (binary), v2 (JSON) or vda5050 (VDA 5050 2.0: poses only, orders driven "
                 "node by node)")
      ->check(CLI::IsMember({"v1", "v2", "vda5050"}))
      ->capture_default_str();
  app.add_option("--rate", o.rate_hz, "reports per robot per second (Hz)")
      ->check(CLI::Range(0.1, 100.0))
      ->capture_default_str();
  app.add_option("--noise", o.noise, "range noise standard deviation (m)")
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  app.add_option("--dropout", o.dropout, "probability that a beam returns nothing")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  app.add_option("--drift", o.drift, "odometry drift (m per sqrt(m) driven)")
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  app.add_option("--heading-drift", o.heading_drift, "odometry heading drift (rad per sqrt(rad) turned)")
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  app.add_option("--odom-frame", o.odom_frame,
                 "where each robot's odometry starts: world (at its true spawn pose) or start (at 0, 0, 0, "
                 "as a real robot)")
      ->check(CLI::IsMember({"world", "start"}))
      ->capture_default_str();
  app.add_option("--seed", o.seed, "random seed (same seed, same run)")->capture_default_str();
  app.add_option("--broker", o.broker, "MQTT broker URL (tcp://, mqtt://, ssl:// or mqtts://HOST:PORT)")
      ->capture_default_str();
  app.add_option("--tls-ca-file", o.tls_ca_file, "PEM CA certificates trusted for the broker (ssl:// URLs)");
  app.add_flag("--random-walk", o.random_walk, "idle robots drive to random reachable targets");
  app.add_option("--speed", o.speed, "simulated seconds per wall-clock second")
      ->check(CLI::Range(0.01, 100.0))
      ->capture_default_str();
  app.add_flag("--mqtt-multiplex", o.mqtt_multiplex, "one MQTT connection for every robot (large fleets)");
  app.add_option(
      "--mqtt-password", o.mqtt_password,
      "each robot logs in as its robot id with this password (a broker with an ACL; prefer a --config file)");
  app.add_option("--units-per-meter", o.units_per_meter, "v1 robot units per metre")
      ->check(CLI::Range(1.0, 10000.0))
      ->capture_default_str();
  app.add_option("--truth-rate", o.truth_rate_hz, "ground truth publications per second (Hz)")
      ->check(CLI::Range(0.1, 50.0))
      ->capture_default_str();
  app.add_option("--beams", o.beams, "range beams per scan")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  app.add_option("--max-range", o.max_range, "range sensor reach (m)")
      ->check(CLI::Range(0.1, 1000.0))
      ->capture_default_str();
  app.add_option("--record-log", o.record_log,
                 "write each simulated robot's scans and odometry as a CARMEN log PREFIX-<robot>.clf while "
                 "running, and the relations of its true poses as PREFIX-<robot>.relations on exit");
  add_play_options(app, o.play);
}

Result<SimulationConfig> simulation_config(const SimOptions& o) {
  SimulationConfig c;
  c.report_period = 1.0 / o.rate_hz;
  c.dt = std::min(kDefaultDt, c.report_period);
  c.speed_factor = o.speed;
  c.seed = o.seed;
  c.random_walk = o.random_walk;
  c.sensor.beams = o.beams;
  c.sensor.max_range = o.max_range;
  c.sensor.range_noise_sd = o.noise;
  c.sensor.dropout = o.dropout;
  c.odometry.drift_per_metre = o.drift;
  c.odometry.drift_per_radian = o.heading_drift;
  c.odom_frame = o.odom_frame == "start" ? OdomFrame::Start : OdomFrame::World;
  if (auto s = validate(c); !s) return Error{"simulation settings: " + s.message()};
  return c;
}

protocol::CodecLimits codec_limits(const SimOptions& o) {
  protocol::CodecLimits limits;
  limits.units_per_meter = o.units_per_meter;
  return limits;
}

Status validate(const SimOptions& o) {
  const bool tls = o.broker.starts_with("ssl://") || o.broker.starts_with("mqtts://");
  if (!tls && !o.broker.starts_with("tcp://") && !o.broker.starts_with("mqtt://"))
    return Error{fmt::format("--broker: '{}' is not tcp://, mqtt://, ssl:// or mqtts://HOST:PORT", o.broker)};
  if (o.vda_robots > o.robots)
    return Error{fmt::format("--vda-robots {} is more than --robots {}", o.vda_robots, o.robots)};
  if (!o.tls_ca_file.empty() && !tls)
    return Error{fmt::format("--tls-ca-file is set but --broker '{}' is not ssl:// or mqtts://", o.broker)};
  if (!o.mqtt_password.empty() && o.mqtt_multiplex)
    return Error{
        "--mqtt-password logs each robot in under its own id: drop --mqtt-multiplex (one shared connection)"};
  if (auto c = simulation_config(o); !c) return c.status();
  if (auto s = protocol::validate(codec_limits(o)); !s) return Error{"--units-per-meter: " + s.message()};
  SLAM_TRY(validate(o.play));
  if (o.play.enabled() && !o.record_log.empty())
    return Error{"--record-log records simulated robots: it cannot be combined with --play"};
  return {};
}

}  // namespace slam::sim
