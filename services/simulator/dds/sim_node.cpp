// The simulation loop and the application of commands. Everything here runs on one thread; the
// only cross-thread hand-off is RobotLinks' waypoint intake.
#include "simulator/dds/sim_node.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "common/core/shutdown.hpp"
#include "protocol/text_check.hpp"

namespace slam::sim {
namespace {

using Clock = std::chrono::steady_clock;

constexpr auto kMinTick = std::chrono::milliseconds(1);
constexpr auto kMaxTick = std::chrono::milliseconds(50);

double seconds(Clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

}  // namespace

SimNode::SimNode(const SimOptions& options, Simulation sim, Counters& counters)
    : options_(options),
      counters_(counters),
      sim_(std::move(sim)),
      robots_(counters.get("robots")),
      steps_(counters.get("steps")),
      loop_overruns_(counters.get("loop_overruns")),
      controls_applied_(counters.get("controls_applied")),
      controls_rejected_(counters.get("controls_rejected")),
      controls_repeated_(counters.get("controls_repeated")),
      waypoints_rejected_(counters.get("waypoints_rejected")),
      waypoints_outside_world_(counters.get("waypoints_outside_world")),
      waypoints_unknown_robot_(counters.get("waypoints_unknown_robot")),
      dds_write_failures_(counters.get("dds_write_failures")),
      robot_contacts_(counters.get("robot_contacts")) {}

SimNode::~SimNode() = default;

Result<std::unique_ptr<SimNode>> SimNode::create(const SimOptions& options, World world, Counters& counters) {
  auto config = simulation_config(options);
  if (!config) return config.error();
  auto sim = Simulation::create(std::move(world), *config);
  if (!sim) return Error{"simulation: " + sim.message()};
  std::unique_ptr<SimNode> node(new SimNode(options, std::move(*sim), counters));

  auto dds = SimDds::create(options.service.domain);
  if (!dds) return dds.error();
  node->dds_ = std::move(*dds);
  auto heartbeat = cyclone::HeartbeatPublisher::start(node->dds_->participant(), "simulator", counters);
  if (!heartbeat) return heartbeat.error();
  node->heartbeat_ = std::move(*heartbeat);

  RobotLinks::Settings link_settings{options.broker,        options.robot_protocol(), options.mqtt_multiplex,
                                     codec_limits(options), options.mqtt_password,    options.tls_ca_file,
                                     options.vda_robots > 0};
  auto links = RobotLinks::create(std::move(link_settings), counters);
  if (!links) return Error{"MQTT: " + links.message()};
  node->links_ = std::move(*links);

  if (!options.record_log.empty()) {
    auto recorder = LogRecorder::create(options.record_log, node->sim_.world().name());
    if (!recorder) return Error{"--record-log: " + recorder.message()};
    node->recorder_ = std::move(*recorder);
  }

  auto ids = node->sim_.spawn_random(static_cast<size_t>(options.robots));
  if (!ids) return Error{"--robots: " + ids.message()};
  node->add_robots(*ids, static_cast<size_t>(options.vda_robots));
  SLAM_TRY(node->dds_->publish_world(node->sim_.world()));
  return node;
}

void SimNode::warn(const std::string& key, const std::string& text) {
  warnings_.warn(key, "{}", text);
}

void SimNode::add_robots(const std::vector<std::string>& ids, size_t vda_robots) {
  for (size_t i = 0; i < ids.size(); ++i) {
    const std::string& id = ids[i];
    const auto speaks = i < vda_robots ? std::optional(RobotProtocol::Vda5050) : std::nullopt;
    if (auto s = links_->add(id, speaks); !s) {
      // A robot that cannot speak MQTT would drive unseen: take it out again.
      warn("link", fmt::format("robot '{}' removed: {}", protocol::escape_for_log(id), s.message()));
      sim_.remove(id);
    }
  }
  robots_.store(static_cast<int64_t>(sim_.robots().size()), std::memory_order_relaxed);
}

void SimNode::reply(uint64_t command_id, const Status& result) {
  replies_sent_.complete(command_id, result);
  if (auto s = dds_->publish_reply(command_id, result); !s) {
    bump(dds_write_failures_);
    warn("reply", s.message());
  }
}

void SimNode::apply_controls() {
  controls_.clear();
  unreadable_controls_.clear();
  if (auto s = dds_->take_controls(controls_, unreadable_controls_); !s) warn("take", s.message());
  for (const UnreadableControl& u : unreadable_controls_) {
    bump(controls_rejected_);
    warn("control", "control ignored: " + u.error);
    reply(u.command_id, Error{u.error});
  }
  for (const ControlCommand& c : controls_) {
    // A requester's retry: applied once (commands run here one by one, so the first copy has its
    // reply by the time a repeat is looked at).
    if (auto verdict = replies_sent_.admit(c.command_id); verdict.admission != Admission::Execute) {
      bump(controls_repeated_);
      if (verdict.reply) reply(c.command_id, *verdict.reply);
      continue;
    }
    auto outcome = apply_control(sim_, c);
    if (!outcome) {
      bump(controls_rejected_);
      warn("control", fmt::format("control {} ignored: {}", c.command_id, outcome.message()));
      reply(c.command_id, Error{outcome.message()});
      continue;
    }
    bump(controls_applied_);
    reply(c.command_id, Status::ok());
    for (const std::string& id : outcome->removed) links_->remove(id);
    add_robots(outcome->spawned);
    if (outcome->world_changed) {
      spdlog::info("world is now '{}' ({} walls)", sim_.world().name(), sim_.world().walls().size());
      if (auto s = dds_->publish_world(sim_.world()); !s) {
        bump(dds_write_failures_);
        warn("world", s.message());
      }
    }
  }
  robots_.store(static_cast<int64_t>(sim_.robots().size()), std::memory_order_relaxed);
}

void SimNode::apply_orders() {
  links_->drain_orders(orders_);
  const Bounds& bounds = sim_.world().bounds();
  for (const WaypointOrder& o : orders_) {
    const Robot* robot = sim_.find(o.robot_id);
    if (robot == nullptr) {
      bump(waypoints_unknown_robot_);  // multiplexed: commands for robots this simulator does not run
      continue;
    }
    if (!o.target) {
      (void)sim_.clear_waypoint(o.robot_id);
      continue;
    }
    // The target is in the robot's odometry frame; where it lies in the world decides.
    if (!bounds.contains(world_from_odom(*robot).transform(*o.target))) {
      bump(waypoints_rejected_);
      bump(waypoints_outside_world_);
      warn("outside",
           fmt::format("waypoint ({:.2f}, {:.2f}) for '{}' ignored: outside world '{}' [{}, {}] x [{}, {}]",
                       o.target->x, o.target->y, protocol::escape_for_log(o.robot_id), sim_.world().name(),
                       bounds.min.x, bounds.max.x, bounds.min.y, bounds.max.y));
      continue;
    }
    (void)sim_.set_waypoint(o.robot_id, *o.target);
  }
}

void SimNode::run_steps(double wall_seconds) {
  const size_t n = sim_.steps_for(wall_seconds);
  for (size_t k = 0; k < n; ++k) {
    const auto reports = sim_.step();
    bump(steps_);
    // Reports come in fleet order, so one forward walk finds each robot's driving state.
    const auto robots = sim_.robots();
    size_t j = 0;
    for (const RobotReport& r : reports) {
      while (j < robots.size() && robots[j].id != r.robot_id) ++j;
      links_->publish(r, j < robots.size() && robots[j].waypoint.has_value());
      if (recorder_)
        if (auto s = recorder_->add(r); !s) warn("record", "--record-log: " + s.message());
    }
  }
  robot_contacts_.store(static_cast<int64_t>(sim_.contacts()), std::memory_order_relaxed);
}

void SimNode::publish_truth() {
  if (auto s = dds_->publish_truth(sim_); !s) {
    bump(dds_write_failures_);
    warn("truth", s.message());
  }
}

void SimNode::finish_recording() {
  if (!recorder_) return;
  if (auto s = recorder_->finish(); !s) {
    spdlog::error("--record-log: {}", s.message());
    return;
  }
  spdlog::info("recorded {} scans of {} robots to {}-<robot>.clf, {} relations to {}-<robot>.relations",
               recorder_->scans(), recorder_->robots(), options_.record_log, recorder_->relations(),
               options_.record_log);
}

void SimNode::run() {
  heartbeat_->set_state(slam_SERVICE_RUNNING);
  spdlog::info("simulating {} robots ({}, {}) in world '{}'; broker {}", sim_.robots().size(),
               options_.protocol,
               options_.mqtt_multiplex ? "one shared MQTT connection" : "one MQTT connection each",
               sim_.world().name(), options_.broker);
  const auto truth_period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(1.0 / options_.truth_rate_hz));
  auto last = Clock::now();
  auto next_truth = last;
  while (!shutdown_requested()) {
    const auto start = Clock::now();
    apply_controls();
    apply_orders();
    run_steps(seconds(start - last));
    last = start;
    links_->poll(start);
    if (start >= next_truth) {
      publish_truth();
      next_truth = std::max(next_truth + truth_period, start);
    }
    const auto tick = std::clamp(std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
                                     sim_.config().dt / sim_.config().speed_factor)),
                                 Clock::duration(kMinTick), Clock::duration(kMaxTick));
    const auto spent = Clock::now() - start;
    if (spent > tick) {
      bump(loop_overruns_);
      continue;
    }
    wait_for_shutdown(std::chrono::duration_cast<std::chrono::milliseconds>(tick - spent));
  }
  heartbeat_->set_state(slam_SERVICE_STOPPING);
  finish_recording();
}

}  // namespace slam::sim
