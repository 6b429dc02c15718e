#pragma once
// slam-gateway's edge and loop, on the house's threading rule (docs/services.md): the MQTT thread
// only decodes (topic, payload) and queues the message in the GatewayIntake; the DDS readers only copy
// their samples into it (pose corrections, waypoint commands, the viewer's MQTT requests, the gateways'
// heartbeats and RobotStates, ForgetRobot); one loop drains it and does everything else: the robot
// registry, observations batched and written, waypoints turned into each robot's odometry frame and
// protocol and published to the broker, requests executed and answered, the robots' states, the fleet
// digests, the MQTT subscriptions. Only the loop touches the gateway's state, so the node holds no lock.
// The MQTT traffic log goes through a bounded queue to its own worker. Several gateways share the robots:
// each robot message reaches one of them (MQTT shared subscriptions) and each robot's waypoints are
// sent by its owner only (Ownership over the gateways' heartbeats), each viewer MQTT request executed by
// the owner of its id only; the protocol a robot speaks is learnt from every gateway's RobotStates.
#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/core/counters.hpp"
#include "common/core/log.hpp"
#include "common/core/ownership.hpp"
#include "common/core/reply_cache.hpp"
#include "common/core/result.hpp"
#include "common/fastdds/fast_topics.hpp"
#include "common/mqtt/mqtt_connection.hpp"
#include "gateway/core/batch_policy.hpp"
#include "gateway/core/command_encoder.hpp"
#include "gateway/core/fleet_digest.hpp"
#include "gateway/core/frame_correction.hpp"
#include "gateway/core/gateway_intake.hpp"
#include "gateway/core/gateway_options.hpp"
#include "gateway/core/inbound_decoder.hpp"
#include "gateway/core/robot_protocols.hpp"
#include "gateway/core/robot_registry.hpp"
#include "gateway/core/traffic_queue.hpp"
#include "gateway/core/vda_orders.hpp"
#include "gateway/dds/traffic_publisher.hpp"
#include "protocol/reject_reason.hpp"

namespace slam::gateway {

class GatewayNode {
 public:
  // Configure: participant, writers, traffic worker, MQTT client, readers. A failure undoes
  // what was done (members are destroyed in reverse order).
  static Result<std::unique_ptr<GatewayNode>> create(const GatewayOptions& options, Counters& counters);
  // Stops the readers and the MQTT client, then writes the last batch with the messages still queued:
  // MQTT has taken those from the broker already.
  ~GatewayNode();
  GatewayNode(const GatewayNode&) = delete;
  GatewayNode& operator=(const GatewayNode&) = delete;

  dds::Participant& participant() { return *participant_; }

  // Faster than the 1 s default: a dead gateway's robots move after options.peer_timeout_s.
  static constexpr std::chrono::milliseconds kHeartbeatPeriod{
      static_cast<std::int64_t>(kGatewayHeartbeatPeriodS * 1000.0)};

  // One loop pass: waits for the first deadline (states, digests, an MQTT reconnection attempt, the
  // pending batch) or for input that cannot wait, takes what the intake holds, then does what is due.
  void run_once();

 private:
  // The loop's one clock. Its deadlines are Clock::time_points; the plain core classes take the same
  // reading as monotonic nanoseconds (Instant::mono_ns), and the wall clock only stamps samples.
  using Clock = std::chrono::steady_clock;
  // One reading of both clocks, taken once per pass.
  struct Tick {
    Clock::time_point at;
    Instant instant;  // {wall ns, `at` in monotonic ns}
    static Tick now();
  };

  struct Metrics {
    explicit Metrics(Counters& c);
    std::atomic<int64_t>& messages_in;
    std::atomic<int64_t>& messages_out;
    std::atomic<int64_t>& observations;
    std::atomic<int64_t>& statuses;
    std::array<std::atomic<int64_t>*, protocol::kRejectReasonCount> rejected;
    std::atomic<int64_t>& robots_refused;
    std::atomic<int64_t>& robots_online;
    std::atomic<int64_t>& robot_states;
    std::atomic<int64_t>& commands;
    std::atomic<int64_t>& commands_sent;
    std::atomic<int64_t>& commands_failed;
    std::atomic<int64_t>& commands_unknown_robot;
    std::atomic<int64_t>& corrections;
    std::atomic<int64_t>& corrections_rejected;
    std::atomic<int64_t>& mqtt_requests;
    std::atomic<int64_t>& mqtt_requests_failed;
    std::atomic<int64_t>& mqtt_requests_repeated;  // retries answered from the cache, not run again
    std::atomic<int64_t>& publish_failures;
    std::atomic<int64_t>& traffic_dropped;
    std::atomic<int64_t>& reconnects;
    std::atomic<int64_t>& write_failures;
    std::atomic<int64_t>& commands_not_owned;
    std::atomic<int64_t>& mqtt_requests_not_owned;  // left to the gateway that owns them
    std::atomic<int64_t>& robots_owned;
    std::atomic<int64_t>& gateways_live;
    std::atomic<int64_t>& robot_protocols_refused;
    std::atomic<int64_t>& robots_forgotten;
    std::atomic<int64_t>& fleet_digests;
    std::atomic<int64_t>& observation_batches;
    std::atomic<int64_t>& scan_error_beams;     // v2 scan beams with range 0 (an error reading), left out
    std::atomic<int64_t>& vda_orders_rejected;  // VDA 5050 orders (updates) a robot's state rejected
    std::atomic<int64_t>& vda_resent;    // VDA 5050 orders and instant actions sent again, not taken yet
    std::atomic<int64_t>& vda_given_up;  // ... and not taken after every send
  };

  GatewayNode(const GatewayOptions& options, Counters& counters);
  Status configure();
  Status make_writers();
  Status make_readers();

  // MQTT receive thread: counts and logs the traffic, decodes, queues. Nothing else.
  void on_mqtt_message(std::string_view topic, std::span<const std::uint8_t> payload);

  // Loop, in the order of a pass (gateway_node.cpp).
  void wait_for_work();
  void take_inputs(const Tick& now);
  void take_correction(const CorrectionInput& input);
  void take_protocol(const ProtocolReport& input);
  void forget_robot(const std::string& id);
  // Expires silent robots and collects the robots whose state goes out in this pass.
  void collect_changed_robots(const Tick& now);
  void dispose_forgotten();
  void publish_states();
  // FleetDigest and FleetPoints, each when its period is over.
  void publish_digests(const Tick& now);
  void publish_subscriptions();
  // Drops silent gateways, logs changes of the live set and counts the robots owned.
  void update_ownership(const Tick& now);

  // Loop, MQTT -> DDS (gateway_inbound.cpp): the registry, the digest's points, the batch.
  void take_inbound(InboundMessage& message);
  void batch_observation(const InboundMessage& message, const AcceptResult& accepted);
  void write_batch();
  // When the pending batch must have left.
  Clock::time_point batch_due() const;
  // How much queued MQTT input fills the pending batch (a first message when there is none).
  InboundWake inbound_wake() const;
  void log_rejection(const InboundMessage& message);
  void log_presence(const InboundMessage& message, const AcceptResult& result);
  // A VDA 5050 message: the robot's address and map, and what its state says of its order.
  void take_vda(const InboundMessage& message);

  // Loop, DDS -> MQTT (gateway_outbound.cpp).
  void send_waypoint(const WaypointInput& command, const Tick& now);
  // VDA 5050 orders and instant actions the robots' states have not shown taken, sent again when due.
  void resend_vda(const Tick& now);
  void answer_request(const MqttRequestInput& request, const Tick& now);
  // The protocol to answer robot `id` in: the fresher of this gateway's registry and the RobotStates.
  std::optional<Protocol> protocol_of(std::string_view id) const;
  Status execute(const MqttRequestInput& request);
  void reply(std::uint64_t request_id, const Status& result);
  // Publishes, counts, logs the traffic.
  Status publish_mqtt(const std::string& topic, std::span<const std::uint8_t> payload, int qos, bool retain);
  void warn(const std::string& key, const std::string& line);

  GatewayOptions options_;
  Clock::duration state_period_;
  Clock::duration digest_period_;
  Clock::duration points_period_;
  Metrics metrics_;
  RateLimitedLog warnings_;
  TrafficQueue traffic_;     // MQTT thread and loop push, the traffic worker pops (its own lock)
  GatewayIntake intake_;     // MQTT thread and DDS readers push, the loop drains
  InboundDecoder decoder_;   // MQTT thread
  InboundMessage received_;  // MQTT thread: the message being decoded (a spent one's buffers)

  // Loop thread only, from here down to the writers.
  GatewayInputs inputs_;
  RobotRegistry registry_;
  FleetDigestBuilder digest_;
  CorrectionTable corrections_;
  RobotProtocols protocols_;
  Ownership ownership_;
  BatchPolicy batch_policy_;
  slam::RobotObservationBatch batch_;
  std::vector<slam::RobotObservation> spare_observations_;  // written batches' elements, reused
  TokenBucket reject_log_budget_{20.0, 20.0};               // rejection lines per second, all robots together
  CommandEncoder encoder_;
  VdaOrders vda_orders_;
  CommandMessages commands_;
  std::vector<OutboundMessage> vda_resends_;
  std::vector<std::string> vda_given_up_;
  std::vector<protocol::Point> remaining_;
  bool presence_changed_ = false;                        // in this pass: a robot's state goes out at once
  std::uint64_t ownership_version_ = ~std::uint64_t{0};  // none logged yet
  Clock::time_point next_owned_count_{};
  Clock::time_point next_states_{};
  Clock::time_point next_digest_{};
  Clock::time_point next_points_{};
  std::vector<std::string> gone_;
  std::vector<RobotRecord> changed_;
  std::vector<std::string> went_offline_;
  std::vector<std::pair<std::string, bool>> forgotten_;  // robot id, had a pose (odometry written)
  slam::RobotState state_;
  slam::RobotOdometry odometry_;
  std::uint64_t published_version_ = 0;
  slam::FleetDigest fleet_digest_;
  slam::FleetPoints fleet_points_;

  // Destroyed bottom-up: readers stop first, then the MQTT client (its callback queues messages),
  // the traffic worker, writers, participant. ~GatewayNode stops the readers and the client itself to
  // write the last batch before the writers go.
  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<dds::Writer<slam::RobotObservationBatch>> observation_writer_;
  std::unique_ptr<dds::Writer<slam::RobotState>> state_writer_;
  std::unique_ptr<dds::Writer<slam::RobotOdometry>> odometry_writer_;
  std::unique_ptr<dds::Writer<slam::MqttSubscriptions>> subscriptions_writer_;
  std::unique_ptr<dds::Writer<slam::MqttReply>> reply_writer_;
  std::unique_ptr<dds::Writer<slam::FleetDigest>> digest_writer_;
  std::unique_ptr<dds::Writer<slam::FleetPoints>> points_writer_;
  ReplyCache<Status> replies_sent_;
  std::unique_ptr<TrafficPublisher> traffic_publisher_;
  std::unique_ptr<mqtt::Connection> mqtt_;
  std::unique_ptr<dds::Reader<slam::PoseCorrection>> correction_reader_;
  std::unique_ptr<dds::Reader<slam::WaypointCommand>> waypoint_reader_;
  std::unique_ptr<dds::Reader<slam::MqttRequest>> request_reader_;
  std::unique_ptr<dds::Reader<slam::Heartbeat>> heartbeat_reader_;
  std::unique_ptr<dds::Reader<slam::RobotState>> state_reader_;
  std::unique_ptr<dds::Reader<slam::ForgetRobot>> forget_reader_;
};

}  // namespace slam::gateway
