#pragma once
// Plain copies of what the viewer receives, converted from the IDL types at the DDS edge
// (viewer_node.cpp), so the core and the panels never include middleware headers.
// Enumerations keep the IDL's order so the edge converts them with a static_cast.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "common/core/alert_kind.hpp"
#include "viewer/core/view_transform.hpp"

namespace slam::viewer {

enum class GoalMode : uint8_t { Idle, Direct, Planned, Square, Explore, Home, Stop };
enum class GoalStatus : uint8_t { None, Active, Reached, Failed };
enum class ServiceState : uint8_t { Starting, Running, Stopping };
enum class CorrectionSource : uint8_t { Identity, Match, Loop, Operator, Restored };
using AlertKind = alerts::Kind;
enum class MissionStatus : uint8_t { Active, Done, Failed, Cancelled };

const char* goal_mode_name(GoalMode m);
const char* goal_status_name(GoalStatus s);
const char* correction_source_name(CorrectionSource s);
const char* mission_status_name(MissionStatus s);

struct GridInfoData {
  uint32_t width = 0;
  uint32_t height = 0;
  double resolution = 0.0;
  Vec2 origin;
  double inflation_radius = 0.0;
};

struct GridSnapshotData {
  uint32_t layout_id = 0;
  uint64_t version = 0;
  GridInfoData info;
  std::vector<uint8_t> cells;
};

// A GridTiles patch (map.idl; decoded by common/core/grid_tiles.hpp).
struct GridPatchData {
  uint32_t layout_id = 0;
  uint64_t version = 0;
  uint32_t tile_side = 0;
  uint8_t encoding = 0;
  std::vector<uint32_t> tiles;
  std::vector<uint8_t> data;
};

// RAW: in the robot's odometry frame (its PoseCorrection maps it into the map frame).
struct ObservationData {
  std::string robot_id;
  uint64_t seq = 0;
  Pose pose;
  std::vector<float> hits_xy;  // x0, y0, x1, y1, ... (odometry frame, metres)
};

// One robot's correction map <- odom (the mapper's PoseCorrection).
struct PoseCorrectionData {
  std::string robot_id;
  uint64_t version = 0;
  Pose map_from_odom;
  uint32_t keyframes = 0;
  uint32_t loop_closures = 0;
  CorrectionSource source = CorrectionSource::Identity;
  double sigma_m = 0.0;  // how well the robot is known in the map (position_sigma)
};

struct RobotStateData {
  std::string robot_id;
  bool protocol_v2 = false;
  bool online = false;
  Pose pose;
  bool has_heading = false;
  int64_t first_seen_ns = 0;
  int64_t last_seen_ns = 0;
  uint64_t messages = 0;
  uint64_t points = 0;
  uint64_t rejected = 0;
  float battery = -1.0f;
  std::string status;
};

// One robot of a gateway's FleetDigest: the pose stream (ten times a second; RobotState, the
// robot's whole record, comes once a second or on a presence change).
struct RobotPoseData {
  std::string robot_id;
  Pose pose;
  bool has_heading = false;
  bool online = false;
  int64_t last_seen_ns = 0;
};

struct RobotPathData {
  std::string robot_id;
  uint64_t goal_id = 0;
  GoalMode mode = GoalMode::Idle;
  GoalStatus status = GoalStatus::None;
  Vec2 target;
  std::vector<Vec2> waypoints;
  uint32_t current = 0;
  std::string reason;
};

// A robot's mission and its progress (NavMission: the planner driving the robot rewrites it).
struct MissionData {
  std::string robot_id;
  uint64_t mission_id = 0;
  std::vector<Vec2> waypoints;
  bool loop = false;
  uint32_t current = 0;  // the waypoint being driven to
  uint32_t laps = 0;
  MissionStatus status = MissionStatus::Active;
  std::string reason;
};

struct HeartbeatData {
  std::string service;
  std::string instance_id;
  uint32_t pid = 0;
  std::string host;
  double uptime_s = 0.0;
  ServiceState state = ServiceState::Starting;
  std::vector<std::pair<std::string, int64_t>> counters;
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

// An operator alert (Alert, raised and cleared by the planners).
struct AlertData {
  std::string alert_id;
  AlertKind kind = AlertKind::RobotOffline;
  std::string subject;
  bool active = false;
  int64_t raised_ns = 0;  // wall clock
  std::string message;
  std::string raised_by;
};

// A ForgetRobot command (from this viewer or any other client).
struct ForgetData {
  std::string robot_id;
};

// A planner's PathReply.
struct PathReplyData {
  uint64_t request_id = 0;
  bool ok = false;     // PLAN_OK
  std::string reason;  // why not, when not ok
  std::vector<Vec2> path;
  double length_m = 0.0;
  double planning_time_s = 0.0;
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
