#pragma once
// What the viewer receives, as plain C++ converted from the IDL types at the DDS edge
// (viewer/dds/node_convert.hpp), so the core and the panels never include middleware headers: the
// messages other services read too are the fleet's (common/core/fleet_messages.hpp); the ones only
// the viewer reads are below. Enumerations keep the IDL's order so the edge converts them by value.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "common/core/fleet_messages.hpp"
#include "viewer/core/view_transform.hpp"

namespace slam::viewer {

// The fleet's enumerations and their names, as the viewer's code spells them.
using msg::AlertKind;
using msg::correction_source_name;
using msg::CorrectionSource;
using msg::goal_mode_name;
using msg::goal_status_name;
using msg::GoalMode;
using msg::GoalStatus;
using msg::mission_status_name;
using msg::MissionStatus;
using msg::ServiceState;

// RAW: in the robot's odometry frame (its PoseCorrection maps it into the map frame).
struct ObservationData {
  std::string robot_id;
  uint64_t seq = 0;
  Pose pose;
  std::vector<float> hits_xy;  // x0, y0, x1, y1, ... (odometry frame, metres)
};

struct MqttEntry {
  uint64_t seq = 0;
  int64_t stamp_ns = 0;
  bool inbound = true;
  std::string topic;
  std::vector<uint8_t> payload;  // at most 1024 octets (the gateway truncates)
  uint32_t payload_size = 0;     // real size
};

struct MqttSubscriptionsData {
  bool connected = false;
  std::string broker;
  std::vector<std::string> filters;
};

struct SimWorldData {
  std::string name;
  double width_m = 0.0, height_m = 0.0;
  std::vector<std::pair<Vec2, Vec2>> walls;
};

struct SimRobotTruthData {
  std::string robot_id;
  Pose true_pose;
  Pose reported_pose;
};

struct SimTruthData {
  bool paused = false;
  std::vector<SimRobotTruthData> robots;
};

// A ForgetRobot command (from this viewer or any other client).
struct ForgetData {
  std::string robot_id;
};

struct MapReplyData {
  uint64_t request_id = 0;
  int result = 0;  // idl MapResult: 0 = MAP_OK
  std::string message;
};

// The gateway's and the simulator's replies: one shape, two types so the intake keeps them apart.
struct RequestReplyData {
  uint64_t request_id = 0;  // SimReply: command_id
  bool ok = false;
  std::string message;
};
struct MqttReplyData : RequestReplyData {};
struct SimReplyData : RequestReplyData {};

}  // namespace slam::viewer
