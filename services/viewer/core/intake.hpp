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
  std::optional<GridSnapshotData> snapshot;  // newest only; patches below came after it
  std::vector<GridPatchData> patches;
  std::vector<ObservationData> observations;
  std::vector<RobotStateData> states;
  std::vector<RobotPoseData> poses;  // in arrival order; the registry keeps the newest
  std::vector<RobotPathData> paths;
  std::vector<MissionData> missions;            // the newest per robot
  std::vector<PoseCorrectionData> corrections;  // the newest per robot
  std::vector<HeartbeatData> heartbeats;
  std::vector<MqttEntry> mqtt;
  std::optional<MqttSubscriptionsData> subscriptions;
  std::optional<SimWorldData> world;
  std::optional<SimTruthData> truth;
  std::vector<MapReplyData> replies;
  std::vector<MqttReplyData> mqtt_replies;
  std::vector<SimReplyData> sim_replies;
  std::vector<AlertData> alerts;
  std::vector<ForgetData> forgets;
  std::vector<PathReplyData> path_replies;
  uint64_t mqtt_dropped = 0;  // entries dropped because the render thread fell behind

  void clear();
};

class Intake {
 public:
  // Bounds the MQTT log backlog between two frames (a flood must not grow memory without end).
  explicit Intake(size_t max_pending_mqtt = 4096) : max_pending_mqtt_(max_pending_mqtt) {}

  void push(GridSnapshotData&& s);
  void push(GridPatchData&& p);
  void push(ObservationData&& o);
  void push(RobotStateData&& s);
  void push(RobotPoseData&& p);
  void push(RobotPathData&& p);
  void push(MissionData&& m);
  void push(PoseCorrectionData&& c);
  void push(HeartbeatData&& h);
  void push(MqttEntry&& e);
  void push(MqttSubscriptionsData&& s);
  void push(SimWorldData&& w);
  void push(SimTruthData&& t);
  void push(MapReplyData&& r);
  void push(MqttReplyData&& r);
  void push(SimReplyData&& r);
  void push(AlertData&& a);
  void push(ForgetData&& f);
  void push(PathReplyData&& r);

  // Moves everything pending into `out` (cleared first); `out`'s buffers are reused next time.
  void drain(IntakeBatch& out);

 private:
  size_t max_pending_mqtt_;
  std::mutex mutex_;
  IntakeBatch pending_;
};

}  // namespace slam::viewer
