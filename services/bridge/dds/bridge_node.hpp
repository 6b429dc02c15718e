#pragma once
// slam-bridge's DDS edge and loop: readers convert samples into plain messages
// (common/fastdds/fleet_messages.hpp) and queue them (nothing else on the listener threads);
// run_once() drains them into the FleetModel and MapView, hands the WebSocket clients' events to
// the Foxglove face, lets it publish what is due, and turns operator goals and path calls into
// NavGoal samples and PathRequests (dds::Requester). The ROS 2 edge (ros_edge.hpp, unless --no-ros)
// reads the same model and map on the same loop.
#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <utility>
#include <variant>
#include <vector>

#include "bridge/core/bridge_options.hpp"
#include "bridge/core/fleet_model.hpp"
#include "bridge/core/foxglove_face.hpp"
#include "bridge/core/map_view.hpp"
#include "bridge/dds/ros_edge.hpp"
#include "bridge/ws/ws_server.hpp"
#include "common/core/counters.hpp"
#include "common/core/log.hpp"
#include "common/core/request_retry.hpp"
#include "common/fastdds/fast_topics.hpp"
#include "common/fastdds/requester.hpp"

namespace slam::bridge {

// What the listener threads hand to the loop.
struct BridgeIntake {
  std::mutex mutex;
  std::vector<msg::RobotPose> states;
  std::vector<msg::RobotPath> paths;
  std::vector<ObservationInput> observations;
  std::vector<msg::Heartbeat> heartbeats;
  std::vector<msg::Alert> alerts;
  std::vector<std::string> forgets;  // robot ids, applied after everything else of the batch
  // Snapshots and patches in arrival order (a patch applies only on top of what came before it).
  std::vector<std::variant<msg::GridSnapshot, msg::GridTiles>> map;
  std::vector<std::pair<PathCall, std::optional<msg::PathReply>>> answers;
};

class BridgeNode final : public OperatorSink, public FrameSink {
 public:
  // The loop wakes this often to publish what is due (the fastest channel period is 0.2 s).
  static constexpr std::chrono::milliseconds kLoopPeriod{20};

  static Result<std::unique_ptr<BridgeNode>> create(const BridgeOptions& options, Counters& counters);
  ~BridgeNode() override;

  dds::Participant& participant() { return *participant_; }
  void run_once();

  void send_goal(const GoalCommand& goal) override;
  void request_path(const PathCall& call) override;
  // The face's frames go out through the WebSocket edge.
  void send_text(ClientId client, const std::string& text) override { ws_->send_text(client, text); }
  void send_binary(ClientId client, const std::string& bytes) override { ws_->send_binary(client, bytes); }

 private:
  BridgeNode(const BridgeOptions& options, Counters& counters);
  Status create_readers();
  void drain_intake();

  std::atomic<int64_t>& received_;
  std::atomic<int64_t>& map_skipped_;
  RateLimitedLog log_;
  RequestIdSource goal_ids_;
  BridgeIntake intake_;
  FleetModel fleet_;
  MapView map_;

  // Declaration order = construction order; destroyed in reverse: readers and the WebSocket
  // server first, the participant last.
  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<dds::Writer<NavGoal>> goal_writer_;
  std::unique_ptr<dds::Writer<PathRequest>> path_writer_;
  std::unique_ptr<dds::Requester<PathReply>> path_requester_;
  // The gateways' fleet digests, not every robot's RobotState and RobotObservation: one sample per
  // gateway and period instead of one datagram per robot message (docs/performance.md, "Bridge").
  std::unique_ptr<dds::Reader<FleetDigest>> digest_reader_;
  std::unique_ptr<dds::Reader<FleetPoints>> points_reader_;
  std::unique_ptr<dds::Reader<RobotPath>> path_reader_;
  std::unique_ptr<dds::Reader<Heartbeat>> heartbeat_reader_;
  std::unique_ptr<dds::Reader<Alert>> alert_reader_;
  std::unique_ptr<dds::Reader<ForgetRobot>> forget_reader_;
  std::unique_ptr<dds::Reader<GridSnapshot>> snapshot_reader_;
  std::unique_ptr<dds::Reader<GridTiles>> tiles_reader_;
  std::unique_ptr<RosEdge> ros_;  // null with --no-ros
  std::unique_ptr<WsServer> ws_;
  std::unique_ptr<FoxgloveFace> face_;
};

}  // namespace slam::bridge
