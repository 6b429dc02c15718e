#pragma once
// The one table of DDS topic names and their QoS, vendor-neutral: the Fast DDS edge (dds.hpp)
// and the Cyclone edge (simulator, interop test) both translate QosSpec from here.
// docs/topics.md mirrors this table for readers. A new topic also goes into dds::all_topics()
// (fastdds/any_topic.cpp: slamctl record and replay) and gets a line in
// compose/security/permissions.rules (SecurityRules checks both agree).
#include <cstdint>

namespace slam::topics {

struct QosSpec {
  bool reliable;
  bool transient_local;  // late joiners get the last `depth` samples per instance
  int32_t depth;         // keep-last depth per instance
  int32_t lease_ms;      // automatic liveliness lease; 0 = infinite
  // A Fast DDS reader's keep-last depth when it differs from the writer's (0: `depth`). A reliable
  // reader holds what arrives after a lost datagram until the gap is repaired, and keep-last
  // replaces held samples without counting them lost: its depth must cover that wait.
  int32_t reader_depth = 0;
};

// Latest value per key, kept for late joiners (robot state, map snapshot, paths, goals).
inline constexpr QosSpec kStateQos{true, true, 1, 0};
// Reliable data stream with a deep history (per key) so bursts are not lost (map patches).
inline constexpr QosSpec kStreamQos{true, false, 200, 0};
// Robot observations in batches (one writer and one key per gateway, ~80-150 batches/s at 10 000
// robot messages/s): reliable, but a writer keeps only the last 64 batches (0.4 s or more of
// traffic) for repair; a lost datagram is repaired within one heartbeat round trip (100-200 ms). A
// reader that falls further behind loses the older batches (counted: SAMPLE_LOST, the mapper's
// `observation_batches_lost`) instead of the history growing: Fast DDS keeps a writer's per-reader
// state in vectors it walks and shifts per sample, so a deep history lets a lagging reader slow the
// writer until the pipeline collapses (docs/performance.md, "Overload"). Readers keep 256 batches:
// what a slow reader's socket still holds while it waits for a repair.
inline constexpr QosSpec kObservationQos{true, false, 64, 0, 256};
// A gateway's fleet digests (one sample per gateway, every robot in it, 50-150 KB at 1000 robots,
// so fragmented): only the latest matters, a newer one replaces what is still being repaired, and
// a late joiner waits one period for the next.
inline constexpr QosSpec kDigestQos{true, false, 1, 0};
// Requests and replies: reliable, volatile, moderate depth.
inline constexpr QosSpec kCommandQos{true, false, 64, 0};
// Heartbeats: latest per service, liveliness tells when a service died.
inline constexpr QosSpec kHeartbeatQos{true, false, 1, 3000};
// High-rate telemetry where only fresh data matters (ground truth, MQTT traffic log).
inline constexpr QosSpec kTelemetryQos{false, false, 64, 0};

struct TopicInfo {
  const char* name;
  QosSpec qos;
};

inline constexpr TopicInfo kRobotObservations{"slam/robot/observations", kObservationQos};
inline constexpr TopicInfo kRobotState{"slam/robot/state", kStateQos};
inline constexpr TopicInfo kRobotOdometry{"slam/robot/odometry", kStateQos};
inline constexpr TopicInfo kPoseCorrection{"slam/robot/correction", kStateQos};
inline constexpr TopicInfo kInitialPose{"slam/robot/initial_pose", kCommandQos};
inline constexpr TopicInfo kPlacementAnswer{"slam/robot/placement_answer", kCommandQos};
inline constexpr TopicInfo kGridSnapshot{"slam/map/snapshot", kStateQos};
inline constexpr TopicInfo kGridTiles{"slam/map/patch", kStreamQos};
inline constexpr TopicInfo kGridConfig{"slam/map/config", kStateQos};
inline constexpr TopicInfo kMapEdit{"slam/map/edit", kCommandQos};
inline constexpr TopicInfo kMapFileRequest{"slam/map/file_request", kCommandQos};
inline constexpr TopicInfo kMapReply{"slam/map/reply", kCommandQos};
inline constexpr TopicInfo kNavGoal{"slam/nav/goal", kStateQos};
inline constexpr TopicInfo kNavMission{"slam/nav/mission", kStateQos};
inline constexpr TopicInfo kRobotPath{"slam/nav/path", kStateQos};
inline constexpr TopicInfo kWaypointCommand{"slam/nav/waypoint", kCommandQos};
inline constexpr TopicInfo kPathRequest{"slam/nav/path_request", kCommandQos};
inline constexpr TopicInfo kPathReply{"slam/nav/path_reply", kCommandQos};
inline constexpr TopicInfo kMqttTraffic{"slam/mqtt/traffic", kTelemetryQos};
inline constexpr TopicInfo kMqttRequest{"slam/mqtt/request", kCommandQos};
inline constexpr TopicInfo kMqttReply{"slam/mqtt/reply", kCommandQos};
inline constexpr TopicInfo kMqttSubscriptions{"slam/mqtt/subscriptions", kStateQos};
inline constexpr TopicInfo kSimControl{"slam/sim/control", kCommandQos};
inline constexpr TopicInfo kSimReply{"slam/sim/reply", kCommandQos};
inline constexpr TopicInfo kSimWorld{"slam/sim/world", kStateQos};
inline constexpr TopicInfo kSimGroundTruth{"slam/sim/ground_truth", kTelemetryQos};
inline constexpr TopicInfo kHeartbeat{"slam/system/heartbeat", kHeartbeatQos};
inline constexpr TopicInfo kAlert{"slam/system/alert", kStateQos};
inline constexpr TopicInfo kForgetRobot{"slam/robot/forget", kCommandQos};
inline constexpr TopicInfo kFleetDigest{"slam/fleet/digest", kDigestQos};
inline constexpr TopicInfo kFleetPoints{"slam/fleet/points", kDigestQos};

// ROS 2 topics (idl/ros2.idl; the bridge's ROS 2 face): ROS 2 puts topic /NAME on DDS as "rt/NAME".
// The map as Nav2's map_server publishes it (reliable, transient-local, keep last 1); frames and
// the RViz2 tools' goals and poses with ROS 2's default QoS (reliable, volatile, keep last 10).
inline constexpr QosSpec kRosDefaultQos{true, false, 10, 0};
inline constexpr TopicInfo kRosMap{"rt/map", kStateQos};
inline constexpr TopicInfo kRosTf{"rt/tf", kRosDefaultQos};
inline constexpr TopicInfo kRosGoalPose{"rt/goal_pose", kRosDefaultQos};
inline constexpr TopicInfo kRosInitialPose{"rt/initialpose", kRosDefaultQos};

}  // namespace slam::topics
