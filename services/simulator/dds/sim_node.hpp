#pragma once
// slam-simulator's service object: owns the Simulation and drives it from one thread. Each loop
// iteration applies operator commands (Cyclone; each gets a SimReply) and waypoints (MQTT intake), runs the
// steps due for the elapsed wall time, publishes every report over MQTT and, at its own rate, ground truth.
// With --record-log each report also goes to its robot's log; the relation files are written at the end.
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/core/counters.hpp"
#include "common/core/log.hpp"
#include "common/core/reply_cache.hpp"
#include "common/core/result.hpp"
#include "common/cyclone/heartbeat.hpp"
#include "simulator/core/log_recorder.hpp"
#include "simulator/core/sim_options.hpp"
#include "simulator/core/simulation.hpp"
#include "simulator/dds/sim_dds.hpp"
#include "simulator/mqtt/robot_link.hpp"

namespace slam::sim {

class SimNode {
 public:
  // Configure: simulation, Cyclone entities, heartbeat, MQTT links, the initial robots. A failure
  // undoes what was done (members are released in reverse) and names the step that failed.
  static Result<std::unique_ptr<SimNode>> create(const SimOptions& options, World world, Counters& counters);
  ~SimNode();

  // Runs until shutdown is requested; heartbeat RUNNING while it does, STOPPING after.
  void run();

 private:
  SimNode(const SimOptions& options, Simulation sim, Counters& counters);
  // The first `vda_robots` of `ids` speak VDA 5050, the others --protocol.
  void add_robots(const std::vector<std::string>& ids, size_t vda_robots = 0);
  void apply_controls();
  void reply(uint64_t command_id, const Status& result);
  void apply_orders();
  void run_steps(double wall_seconds);
  void publish_truth();
  void finish_recording();
  void warn(const std::string& key, const std::string& text);

  SimOptions options_;
  Counters& counters_;
  Simulation sim_;
  RateLimitedLog warnings_;
  std::atomic<int64_t>& robots_;
  std::atomic<int64_t>& steps_;
  std::atomic<int64_t>& loop_overruns_;
  std::atomic<int64_t>& controls_applied_;
  std::atomic<int64_t>& controls_rejected_;
  std::atomic<int64_t>& controls_repeated_;  // retries answered from the cache, not applied again
  std::atomic<int64_t>& waypoints_rejected_;
  std::atomic<int64_t>& waypoints_outside_world_;
  std::atomic<int64_t>& waypoints_unknown_robot_;
  std::atomic<int64_t>& dds_write_failures_;
  std::atomic<int64_t>& robot_contacts_;  // Simulation::contacts(): robots touching each other

  // Declared in set-up order, so teardown runs in reverse: robots go offline, then DDS goes.
  std::unique_ptr<SimDds> dds_;
  std::unique_ptr<cyclone::HeartbeatPublisher> heartbeat_;
  std::unique_ptr<RobotLinks> links_;
  std::optional<LogRecorder> recorder_;  // --record-log

  ReplyCache<Status> replies_sent_;
  std::vector<ControlCommand> controls_;
  std::vector<UnreadableControl> unreadable_controls_;
  std::vector<WaypointOrder> orders_;
};

}  // namespace slam::sim
