#pragma once
// The fleet's MQTT side: each simulated robot speaks the robot protocol (v1, v2 or VDA 5050) exactly
// as a real one does, over its own connection (client id = robot id) or one shared multiplexed
// connection. Reports go out from the simulation loop; waypoint commands arrive on paho threads,
// are decoded and checked there, and wait in a locked intake the loop drains.
#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "common/core/counters.hpp"
#include "common/core/log.hpp"
#include "common/core/result.hpp"
#include "common/mqtt/mqtt_connection.hpp"
#include "protocol/codec_types.hpp"
#include "protocol/vda5050_codec.hpp"
#include "simulator/core/geometry.hpp"
#include "simulator/core/report.hpp"
#include "simulator/core/sim_options.hpp"

namespace slam::sim {

// A decoded server command for one robot. No target: stop (a v2 path with no points).
struct WaypointOrder {
  std::string robot_id;
  std::optional<Vec2> target;
};

class RobotLinks {
 public:
  static constexpr double kStatusPeriodS = 5.0;    // simulated seconds between repeated v2 statuses
  static constexpr double kVdaStatePeriodS = 1.0;  // simulated seconds between VDA 5050 states at most
  // A VDA robot's manufacturer; its serialNumber is its robot id.
  static constexpr std::string_view kVdaManufacturer = "slamfleet-sim";
  // How many of its latest instant actions a VDA robot lists in its state.
  static constexpr std::size_t kVdaActionsListed = 8;

  struct Settings {
    std::string broker;
    RobotProtocol protocol = RobotProtocol::V1;
    bool multiplex = false;
    protocol::CodecLimits limits;
    // Not empty: each robot's own connection logs in as its robot id with this password (a broker
    // with a password file and an ACL keyed by user name, like compose/mosquitto).
    std::string password;
    std::string tls_ca_file;  // trusted for an ssl:// broker (empty: the system's CAs)
    bool vda_robots = false;  // some robots speak VDA 5050 whatever `protocol` says (add())
  };

  // Registers the counters it keeps (reports_sent, waypoints_received, mqtt_reconnects, ...) and,
  // when multiplexed, opens the shared connection.
  static Result<std::unique_ptr<RobotLinks>> create(Settings settings, Counters& counters);
  // v2 robots announce "offline" first; every connection then closes cleanly, all at once.
  ~RobotLinks();
  RobotLinks(const RobotLinks&) = delete;
  RobotLinks& operator=(const RobotLinks&) = delete;

  // Starts speaking for `robot_id` (its own connection unless multiplexed) in `speaks`, by default
  // settings.protocol.
  Status add(const std::string& robot_id, std::optional<RobotProtocol> speaks = std::nullopt);
  // Stops speaking for it; a v2 robot says "offline" first.
  void remove(const std::string& robot_id);

  // Publishes the robot's report (v1 adv, or v2 scan stamped with the simulated time, plus a status
  // when `driving` changed, the connection is new, or kStatusPeriodS passed, so late subscribers
  // learn it too). Unknown robots and failed publishes are counted, never fatal.
  void publish(const RobotReport& report, bool driving);

  // Reconnection attempts that are due and the mqtt_connected gauge; call every loop iteration.
  void poll(std::chrono::steady_clock::time_point now);

  // Moves the commands received since the last call into `out` (cleared first).
  void drain_orders(std::vector<WaypointOrder>& out);

 private:
  // A VDA 5050 robot's side: the order it drives, node by node (released nodes only; the horizon waits
  // for an update stitched at the last released node).
  struct VdaRobot {
    std::string state_topic;
    std::string visualization_topic;
    std::string connection_topic;
    std::uint32_t state_headers = 0;
    std::uint32_t visualization_headers = 0;
    std::uint32_t connection_headers = 0;
    protocol::VdaOrder order;                             // ids and map of the order taken last
    std::vector<protocol::VdaNode> nodes_left;            // not passed yet, base then horizon
    protocol::VdaNode last_node;                          // passed last (id and sequence id)
    std::optional<std::uint32_t> steering_to;             // sequence id of the node the simulation drives to
    bool paused = false;                                  // startPause: it stands until stopPause
    std::vector<protocol::VdaActionState> actions_taken;  // its latest instant actions, all finished
    bool state_due = true;
    double state_time_s = -1e300;
  };
  // An order or instant actions, decoded on a paho thread, applied by the loop.
  struct VdaCommand {
    std::string robot_id;
    protocol::VdaOrder order;  // empty order_id: instant actions
    bool cancel = false;
    std::optional<bool> pause;            // startPause (true) or stopPause (false), the last of them
    std::vector<std::string> action_ids;  // of the instant actions, for the state's actionStates
  };

  struct Endpoint {
    std::string report_topic;
    std::string status_topic;
    std::unique_ptr<mqtt::Connection> own_link;  // per-robot mode
    mqtt::Connection* link = nullptr;
    uint64_t status_connects = 0;   // link->connects() when the last status went out
    double status_time_s = -1e300;  // simulated time of the last status
    bool driving = false;
    RobotProtocol protocol = RobotProtocol::V1;
    VdaRobot vda;
  };

  RobotLinks(Settings settings, Counters& counters);
  // The endpoint on the shared connection, or on its own one subscribing `subscriptions` with `will`.
  Status attach(const std::string& robot_id, Endpoint e, std::vector<std::string> subscriptions,
                std::optional<mqtt::Will> will);
  Result<std::unique_ptr<mqtt::Connection>> open(const std::string& client_id,
                                                 std::vector<std::string> subscriptions,
                                                 std::optional<mqtt::Will> will);
  void on_message(std::string_view topic, std::span<const uint8_t> payload);
  void reject(std::string_view robot_id, const std::string& reason, const std::string& detail);
  void send(Endpoint& e, const std::string& topic, std::span<const uint8_t> payload);
  void send_status(Endpoint& e, bool driving, double time_s);
  // VDA 5050 (robot_link_vda.cpp).
  Status add_vda(const std::string& robot_id, Endpoint& e, std::vector<std::string>& subscriptions,
                 std::optional<mqtt::Will>& will);
  void publish_vda(Endpoint& e, const std::string& robot_id, const RobotReport& report, bool driving);
  void send_connection(Endpoint& e, const std::string& robot_id, protocol::VdaConnection connection);
  bool on_vda_message(std::string_view topic, std::span<const uint8_t> payload);
  void take_vda(const VdaCommand& command, std::vector<WaypointOrder>& out);
  // The waypoint for the robot's next released node, or a stop (none, or paused), when it differs from
  // what was sent.
  void steer(Endpoint& e, const std::string& robot_id, std::vector<WaypointOrder>& out);

  Settings settings_;
  std::atomic<int64_t>& reports_sent_;
  std::atomic<int64_t>& reports_dropped_;
  std::atomic<int64_t>& waypoints_received_;
  std::atomic<int64_t>& waypoints_rejected_;
  std::atomic<int64_t>& orders_dropped_;
  std::atomic<int64_t>& mqtt_connected_;  // gauge, refreshed by poll()
  std::atomic<int64_t>& mqtt_reconnects_;
  std::atomic<int64_t>& mqtt_connect_failures_;
  RateLimitedLog warnings_;

  std::unique_ptr<mqtt::Connection> shared_link_;  // multiplexed mode
  std::unordered_map<std::string, Endpoint> endpoints_;

  std::mutex intake_mutex_;
  std::vector<WaypointOrder> intake_;
  std::vector<VdaCommand> vda_intake_;
  std::vector<VdaCommand> vda_commands_;  // loop: the intake's, being applied
  std::vector<WaypointOrder> steering_;   // loop: waypoints publish_vda() decided
  protocol::VdaTree vda_tree_;

  // Encoding scratch, reused report after report.
  std::vector<protocol::Point> hits_;
  std::vector<uint8_t> bytes_;
  std::string text_;
  std::vector<double> ranges_;
};

}  // namespace slam::sim
