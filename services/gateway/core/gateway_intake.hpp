#pragma once
// What the gateway's threads hand to its loop, behind one mutex: the MQTT thread's decoded messages
// and plain copies of the DDS readers' samples. Pushers only queue (the MQTT thread swaps its decoded
// message in and gets a spent one's buffers back, so neither side allocates once warm); the loop
// sleeps here until its next deadline or until input that cannot wait arrives, then takes everything
// in one swap. Each kind keeps its arrival order. The MQTT thread waits while max_inbound messages
// are queued, so a flood the loop cannot follow backs up at the broker, not in the gateway's memory.
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <mutex>
#include <string>
#include <vector>

#include "gateway/core/frame_correction.hpp"
#include "gateway/core/inbound_decoder.hpp"
#include "gateway/core/robot_protocols.hpp"
#include "protocol/codec_types.hpp"

namespace slam::gateway {

// A PoseCorrection: the robot's map_from_odom.
struct CorrectionInput {
  std::string robot_id;
  Correction correction;
};

// A WaypointCommand, in the map frame.
struct WaypointInput {
  std::string robot_id;
  std::uint64_t seq = 0;
  protocol::Point waypoint;
  std::vector<protocol::Point> remaining;  // the rest of the path (v2 robots)
};

// What an MqttRequest asks for; an unknown value of the IDL enum is kept as it came.
enum class RequestKind : std::uint32_t { Publish = 0, Subscribe = 1, Unsubscribe = 2 };

// An MqttRequest from the viewer or slamctl.
struct MqttRequestInput {
  std::uint64_t request_id = 0;
  RequestKind kind = RequestKind::Publish;
  std::string topic;  // topic or filter
  std::vector<std::uint8_t> payload;
  std::uint32_t qos = 0;
  bool retain = false;
};

// Another gateway's heartbeat (the readers drop every other service's).
struct PeerHeartbeat {
  std::string instance_id;
  bool stopping = false;
};

// A RobotState from any gateway: the protocol its robot speaks.
struct ProtocolReport {
  std::string robot_id;
  LearntProtocol report;
};

// Everything queued between two loop passes, each kind in arrival order.
struct GatewayInputs {
  std::vector<InboundMessage> inbound;  // MQTT thread
  std::vector<CorrectionInput> corrections;
  std::vector<WaypointInput> waypoints;
  std::vector<MqttRequestInput> requests;
  std::vector<PeerHeartbeat> heartbeats;
  std::vector<ProtocolReport> protocols;
  std::vector<std::string> forgets;  // ForgetRobot: robot ids

  bool empty() const;
};

// How much queued MQTT input wakes the loop early: `messages` messages or `points` obstacle points,
// whichever comes first (what fills the loop's pending batch; a first message when it has none).
struct InboundWake {
  std::size_t messages = 1;
  std::size_t points = std::numeric_limits<std::size_t>::max();
};

class GatewayIntake {
 public:
  using Clock = std::chrono::steady_clock;

  // A loop pass takes everything queued; 4096 messages are 0.4 s of a 1000-robot fleet at 10 Hz.
  static constexpr std::size_t kMaxQueuedInbound = 4096;

  explicit GatewayIntake(std::size_t max_inbound = kMaxQueuedInbound) : max_inbound_(max_inbound) {}

  // MQTT thread: queues `message` and leaves a spent message in its place (buffers to reuse,
  // contents unspecified). Waits while max_inbound messages are queued, until a drain or close().
  void push(InboundMessage& message);
  // DDS reader threads. Waypoints, requests and forgets wake the loop: they are acted on at once;
  // the others wait for its next pass.
  void push(CorrectionInput input);
  void push(WaypointInput input);
  void push(MqttRequestInput input);
  void push(PeerHeartbeat input);
  void push(ProtocolReport input);
  void push_forget(std::string robot_id);

  // Loop: sleeps until `deadline`, or until a waypoint, a request or a forget is queued, or as much
  // MQTT input as `wake` says (a full queue always wakes it). Returns at once when that is queued already.
  void wait_until(Clock::time_point deadline, InboundWake wake = {});
  // Loop: moves everything queued into `out`. The messages `out` held before (handled by now) go
  // back to the MQTT thread for their buffers.
  void drain(GatewayInputs& out);
  // Shutdown: the MQTT thread no longer waits for room (nothing drains once the loop has stopped).
  void close();

 private:
  // Holding mutex_: whether the waiting loop must wake now.
  bool ready() const;
  // Holding mutex_, after a push: true (once per wait) when the loop must be notified.
  bool take_notify();

  const std::size_t max_inbound_;
  std::mutex mutex_;
  std::condition_variable wake_;  // the loop
  std::condition_variable room_;  // the MQTT thread, while the inbound queue is full
  GatewayInputs pending_;
  std::size_t pending_points_ = 0;     // obstacle points of pending_.inbound
  std::vector<InboundMessage> spare_;  // spent messages, their buffers kept for the MQTT thread
  InboundWake wake_on_{};              // of the wait in progress
  bool waiting_ = false;               // the loop sleeps in wait_until
  bool notified_ = false;              // and was notified already
  bool closed_ = false;
};

}  // namespace slam::gateway
