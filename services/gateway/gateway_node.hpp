#pragma once
// slam-gateway's edges: MQTT in (decode, registry, observations batched and written from the
// MQTT thread when a batch is full, from the loop when it has waited --batch-ms), DDS in (pose corrections
// kept per robot; waypoint commands, turned into the robot's odometry frame, and the viewer's MQTT requests,
// published to the broker from the reader threads), and a loop that turns robot presence, poses (in the map
// frame, the raw odometry beside) and subscriptions into state samples. The MQTT traffic log goes through a
// bounded queue to its own worker. Several gateways share the robots: each robot message reaches one of them
// (MQTT shared subscriptions) and each robot's waypoints are sent by its owner only (Ownership over the
// gateways' heartbeats), each viewer MQTT request executed by the owner of its id only; the protocol a robot
// speaks is learnt from every gateway's RobotStates.
#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/core/counters.hpp"
#include "common/core/log.hpp"
#include "common/core/ownership.hpp"
#include "common/core/reply_cache.hpp"
#include "common/core/result.hpp"
#include "common/fastdds/fast_topics.hpp"
#include "common/mqtt/mqtt_connection.hpp"
#include "gateway/batch_policy.hpp"
#include "gateway/command_encoder.hpp"
#include "gateway/fleet_digest.hpp"
#include "gateway/frame_correction.hpp"
#include "gateway/gateway_options.hpp"
#include "gateway/inbound_decoder.hpp"
#include "gateway/robot_protocols.hpp"
#include "gateway/robot_registry.hpp"
#include "gateway/traffic_publisher.hpp"
#include "gateway/traffic_queue.hpp"
#include "protocol/reject_reason.hpp"

namespace slam::gateway {

class GatewayNode {
 public:
  // Configure: participant, writers, traffic worker, MQTT client, readers. A failure undoes
  // what was done (members are destroyed in reverse order).
  static Result<std::unique_ptr<GatewayNode>> create(const GatewayOptions& options, Counters& counters);
  // Stops the readers and the MQTT client, then writes the last batch: MQTT has taken those
  // messages from the broker already.
  ~GatewayNode();
  GatewayNode(const GatewayNode&) = delete;
  GatewayNode& operator=(const GatewayNode&) = delete;

  dds::Participant& participant() { return *participant_; }

  // Faster than the 1 s default: a dead gateway's robots move after options.peer_timeout_s.
  static constexpr std::chrono::milliseconds kHeartbeatPeriod{
      static_cast<std::int64_t>(kGatewayHeartbeatPeriodS * 1000.0)};

  // One loop pass. It waits up to the state period, less when a robot appears, changes presence or
  // gets a new correction, or when an MQTT reconnection attempt, a fleet digest or a batch of
  // observations is due. Then it writes a due batch, starts a due attempt and marks silent robots
  // offline. It publishes the state and odometry of each robot that changed, the fleet digests
  // when due, and the MQTT subscriptions when they changed.
  void run_once();

 private:
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
    std::atomic<int64_t>& scan_error_beams;  // v2 scan beams with range 0, left out
  };

  GatewayNode(const GatewayOptions& options, Counters& counters);
  Status configure();

  // MQTT receive thread.
  void on_mqtt_message(std::string_view topic, std::span<const std::uint8_t> payload);
  void log_rejection(std::string_view topic, Instant now);
  void log_presence(std::string_view robot_id, const AcceptResult& result);
  // MQTT thread, or the loop holding inbound_mutex_: writes the pending observations in one sample.
  void write_batch();
  // Holding inbound_mutex_: makes the loop wake when the current batch is due.
  void arm_batch_deadline();
  // Loop: writes the batch if its oldest observation has waited long enough, else wakes again then.
  void flush_batch_when_due(std::int64_t now_mono_ns);
  // DDS reader threads.
  void on_correction(const slam::PoseCorrection& sample);
  void on_waypoint(const slam::WaypointCommand& command);
  void on_request(const slam::MqttRequest& request);
  void on_heartbeat(const slam::Heartbeat& heartbeat);
  void on_robot_state(const slam::RobotState& state);
  void on_forget(const slam::ForgetRobot& command);
  // Loop: disposes the forgotten robots' state instances (late joiners must not get them).
  void dispose_forgotten();
  // The protocol to answer robot `id` in: the fresher of this gateway's registry and the RobotStates.
  std::optional<Protocol> protocol_of(std::string_view id);
  Status execute(const slam::MqttRequest& request);
  void reply(std::uint64_t request_id, const Status& result);
  // Any thread: publishes, counts, logs the traffic.
  Status publish_mqtt(const std::string& topic, std::span<const std::uint8_t> payload, int qos, bool retain);
  void warn(const std::string& key, const std::string& line);

  void publish_states();
  // Loop: FleetDigest and FleetPoints, each when its period is over.
  void publish_digests(std::int64_t now_mono_ns, std::int64_t now_wall_ns);
  void publish_subscriptions();
  // Loop: drops silent gateways, logs changes of the live set and counts the robots owned.
  void update_ownership(std::int64_t now_mono_ns);

  GatewayOptions options_;
  std::chrono::milliseconds period_;
  Metrics metrics_;
  RateLimitedLog warnings_;
  TrafficQueue traffic_;

  // Registry: MQTT thread, waypoint reader thread and loop. urgent_ wakes the loop.
  std::mutex registry_mutex_;
  std::condition_variable loop_wake_;
  bool urgent_ = false;
  std::int64_t batch_due_ns_ = 0;  // monotonic; when the loop must write a pending batch (0: none)
  RobotRegistry registry_;
  std::vector<std::string> forget_;  // ForgetRobot commands not applied yet
  FleetDigestBuilder digest_;        // threads: see fleet_digest.hpp

  // Correction reader thread writes; waypoint reader thread and loop read. Never held with
  // registry_mutex_.
  std::mutex corrections_mutex_;
  CorrectionTable corrections_;

  // MQTT receive thread, and the loop to write a due batch. Taken before registry_mutex_, never after.
  std::mutex inbound_mutex_;
  InboundDecoder decoder_;
  BatchPolicy batch_policy_;
  slam::RobotObservationBatch batch_;
  std::vector<slam::RobotObservation> spare_observations_;  // written batches' elements, reused
  TokenBucket reject_log_budget_{20.0, 20.0};               // rejection lines per second, all robots together

  // Waypoint reader thread.
  std::mutex outbound_mutex_;
  CommandEncoder encoder_;
  CommandMessages commands_;
  std::vector<protocol::Point> remaining_;

  // Heartbeat reader thread, waypoint reader thread and loop.
  std::mutex ownership_mutex_;
  Ownership ownership_;

  // RobotState reader thread writes; waypoint reader thread and loop read.
  std::mutex protocols_mutex_;
  RobotProtocols protocols_;

  // Loop thread.
  std::uint64_t ownership_version_ = ~std::uint64_t{0};  // none logged yet
  std::int64_t next_owned_count_ns_ = 0;
  std::vector<std::string> gone_;
  std::vector<RobotRecord> changed_;
  std::vector<std::string> went_offline_;
  std::vector<std::pair<std::string, bool>> forgotten_;  // robot id, had a pose (odometry written)
  slam::RobotState state_;
  slam::RobotOdometry odometry_;
  std::uint64_t published_version_ = 0;
  std::int64_t next_digest_ns_ = 0;  // monotonic
  std::int64_t next_states_ns_ = 0;  // monotonic
  std::int64_t next_points_ns_ = 0;
  slam::FleetDigest fleet_digest_;
  slam::FleetPoints fleet_points_;

  // Destroyed bottom-up: readers stop first (they publish through the MQTT client), then the MQTT
  // client (its callbacks write observations and traffic), the traffic worker, writers, participant.
  // ~GatewayNode stops the readers and the client itself to write the last batch before the writers go.
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
