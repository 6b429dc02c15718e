#pragma once
// The one hand-over point between DDS listener threads and the render thread: listeners push
// under a short lock, the render thread swaps everything out once per frame. Nothing here
// touches GL, and nothing blocks longer than a vector push.
#include <cstdint>
#include <mutex>
#include <optional>
#include <vector>

#include "viewer/core/intake_types.hpp"

namespace slam::viewer {

// Everything received since the last drain, in arrival order per kind.
struct IntakeBatch {
  std::optional<msg::GridSnapshot> snapshot;  // newest only; patches below came after it
  std::vector<msg::GridTiles> patches;
  std::vector<ObservationData> observations;
  std::vector<msg::RobotState> states;
  std::vector<msg::RobotPose> poses;  // in arrival order; the registry keeps the newest
  std::vector<msg::RobotPath> paths;
  std::vector<msg::Mission> missions;            // the newest per robot
  std::vector<msg::PoseCorrection> corrections;  // the newest per robot
  std::vector<msg::Heartbeat> heartbeats;
  std::vector<MqttEntry> mqtt;
  std::optional<MqttSubscriptionsData> subscriptions;
  std::optional<SimWorldData> world;
  std::optional<SimTruthData> truth;
  std::vector<MapReplyData> replies;
  std::vector<MqttReplyData> mqtt_replies;
  std::vector<SimReplyData> sim_replies;
  std::vector<msg::Alert> alerts;
  std::vector<ForgetData> forgets;
  std::vector<msg::PathReply> path_replies;
  uint64_t mqtt_dropped = 0;  // entries dropped because the render thread fell behind

  void clear();
};

class Intake {
 public:
  // Bounds the MQTT log backlog between two frames (a flood must not grow memory without end).
  explicit Intake(size_t max_pending_mqtt = 4096) : max_pending_mqtt_(max_pending_mqtt) {}

  void push(msg::GridSnapshot&& s);
  void push(msg::GridTiles&& p);
  void push(ObservationData&& o);
  void push(msg::RobotState&& s);
  void push(msg::RobotPose&& p);
  void push(msg::RobotPath&& p);
  void push(msg::Mission&& m);
  void push(msg::PoseCorrection&& c);
  void push(msg::Heartbeat&& h);
  void push(MqttEntry&& e);
  void push(MqttSubscriptionsData&& s);
  void push(SimWorldData&& w);
  void push(SimTruthData&& t);
  void push(MapReplyData&& r);
  void push(MqttReplyData&& r);
  void push(SimReplyData&& r);
  void push(msg::Alert&& a);
  void push(ForgetData&& f);
  void push(msg::PathReply&& r);

  // Moves everything pending into `out` (cleared first); `out`'s buffers are reused next time.
  void drain(IntakeBatch& out);

 private:
  size_t max_pending_mqtt_;
  std::mutex mutex_;
  IntakeBatch pending_;
};

}  // namespace slam::viewer
