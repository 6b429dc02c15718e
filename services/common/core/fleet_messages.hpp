#pragma once
// The messages the services read from one another, as plain C++: one definition for the viewer, the
// bridge, slamctl and the planner, so their cores never include a DDS header. Each struct holds the
// fields of the IDL type it is named after (idl/*.idl) that its readers use; the Fast DDS edge
// converts them (common/fastdds/fleet_messages.hpp). Enumerations keep the IDL's order, which that
// conversion checks at compile time.
//
// Names: each enumeration's values are spelled once here, as the tools print them ("planned",
// "reached", ...). A value outside the enumeration (a newer peer's) is named "?".
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/core/alert_kind.hpp"
#include "common/core/geometry.hpp"

namespace slam::msg {

// nav.idl
enum class GoalMode : uint8_t { Idle, Direct, Planned, Square, Explore, Home, Stop };
enum class SquareAnchor : uint8_t { Corner, Centred };
enum class GoalStatus : uint8_t { None, Active, Reached, Failed };
enum class MissionStatus : uint8_t { Active, Done, Failed, Cancelled };
enum class PlanStatus : uint8_t { Ok, StartBlocked, GoalBlocked, NoPath, Timeout, NoMap, InvalidRequest };
// correction.idl
enum class CorrectionSource : uint8_t { Identity, Match, Loop, Operator, Restored };
enum class RobotPlacement : uint8_t { Placed, Placing, Unplaced, Lost };
// system.idl
enum class ServiceState : uint8_t { Starting, Running, Stopping };
using AlertKind = alerts::Kind;

// The names of each enumeration's values, indexed by value.
inline constexpr std::array<const char*, 7> kGoalModeNames{"idle",    "direct", "planned", "square",
                                                           "explore", "home",   "stop"};
inline constexpr std::array<const char*, 2> kSquareAnchorNames{"corner", "centred"};
inline constexpr std::array<const char*, 4> kGoalStatusNames{"none", "active", "reached", "failed"};
inline constexpr std::array<const char*, 4> kMissionStatusNames{"active", "done", "failed", "cancelled"};
// For people and logs: the IDL enumerators without their prefix.
inline constexpr std::array<const char*, 7> kPlanStatusNames{
    "OK", "START_BLOCKED", "GOAL_BLOCKED", "NO_PATH", "TIMEOUT", "NO_MAP", "INVALID_REQUEST"};
// For machine-readable output (JSON, counter names).
inline constexpr std::array<const char*, 7> kPlanStatusIds{
    "ok", "start_blocked", "goal_blocked", "no_path", "timeout", "no_map", "invalid_request"};
// For machine-readable output (slamctl, JSON).
inline constexpr std::array<const char*, 5> kCorrectionSourceIds{"identity", "match", "loop", "operator",
                                                                 "restored"};
// For people (the viewer's panels).
inline constexpr std::array<const char*, 5> kCorrectionSourceNames{"identity", "match", "loop closure",
                                                                   "operator", "restored"};
inline constexpr std::array<const char*, 4> kRobotPlacementNames{"placed", "placing", "unplaced", "lost"};
inline constexpr std::array<const char*, 3> kServiceStateNames{"starting", "running", "stopping"};

// names[value], or "?" for a value outside the enumeration.
template <class Enum, std::size_t N>
constexpr const char* name_of(Enum value, const std::array<const char*, N>& names) {
  const auto i = static_cast<std::size_t>(value);
  return i < N ? names[i] : "?";
}

// The value named `name` in `names`, if any.
template <class Enum, std::size_t N>
constexpr std::optional<Enum> parse_name(std::string_view name, const std::array<const char*, N>& names) {
  for (std::size_t i = 0; i < N; ++i)
    if (name == names[i]) return static_cast<Enum>(i);
  return std::nullopt;
}

constexpr const char* goal_mode_name(GoalMode m) {
  return name_of(m, kGoalModeNames);
}
constexpr std::optional<GoalMode> parse_goal_mode(std::string_view name) {
  return parse_name<GoalMode>(name, kGoalModeNames);
}
constexpr const char* square_anchor_name(SquareAnchor a) {
  return name_of(a, kSquareAnchorNames);
}
constexpr const char* goal_status_name(GoalStatus s) {
  return name_of(s, kGoalStatusNames);
}
constexpr const char* mission_status_name(MissionStatus s) {
  return name_of(s, kMissionStatusNames);
}
constexpr const char* plan_status_name(PlanStatus s) {
  return name_of(s, kPlanStatusNames);
}
constexpr const char* plan_status_id(PlanStatus s) {
  return name_of(s, kPlanStatusIds);
}
constexpr const char* correction_source_name(CorrectionSource s) {
  return name_of(s, kCorrectionSourceNames);
}
constexpr const char* correction_source_id(CorrectionSource s) {
  return name_of(s, kCorrectionSourceIds);
}
constexpr const char* robot_placement_name(RobotPlacement p) {
  return name_of(p, kRobotPlacementNames);
}
constexpr const char* service_state_name(ServiceState s) {
  return name_of(s, kServiceStateNames);
}

// robot.idl RobotState: a robot's whole record, from its gateway once a second or on a presence
// change. Map frame.
struct RobotState {
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
  float battery = -1.0f;  // 0..1, negative when unknown
  std::string status;     // robot-reported (v2), empty when unknown
};

// robot.idl DigestRobot: one robot of a gateway's FleetDigest, the pose stream (ten times a second).
// Map frame.
struct RobotPose {
  std::string robot_id;
  Pose pose;
  bool has_heading = false;
  bool online = false;
  int64_t last_seen_ns = 0;  // the robot's last message, Unix epoch: the newest wins across gateways
};

// correction.idl PoseCorrection: one robot's correction map <- odom, from the mapper.
struct PoseCorrection {
  std::string robot_id;
  uint64_t version = 0;
  int64_t stamp_ns = 0;
  Pose map_from_odom;
  std::array<double, 6> covariance{};  // upper triangle of (x, y, theta): position_sigma() reads it
  uint32_t segment = 0;
  uint32_t keyframes = 0;
  uint32_t loop_closures = 0;
  CorrectionSource source = CorrectionSource::Identity;
  RobotPlacement placement = RobotPlacement::Placed;
  double localisation_score = 1.0;
};

// nav.idl RobotPath: the path a robot follows, from the planner that drives it. Map frame.
struct RobotPath {
  std::string robot_id;
  uint64_t goal_id = 0;
  GoalMode mode = GoalMode::Idle;
  GoalStatus status = GoalStatus::None;
  Vec2 target;
  std::vector<Vec2> waypoints;
  uint32_t current = 0;  // index of the waypoint being driven to
  std::string reason;    // why it failed, empty otherwise
};

// nav.idl NavMission: a robot's mission and its progress (the planner driving the robot rewrites it).
struct Mission {
  std::string robot_id;
  uint64_t mission_id = 0;
  std::vector<Vec2> waypoints;
  bool loop = false;
  uint32_t current = 0;  // the waypoint being driven to
  uint32_t laps = 0;
  MissionStatus status = MissionStatus::Active;
  std::string reason;
};

// nav.idl PathReply: a planner's answer to a path request.
struct PathReply {
  uint64_t request_id = 0;
  PlanStatus status = PlanStatus::Ok;
  std::string reason;  // why not, when not Ok
  std::vector<Vec2> path;
  double length_m = 0.0;
  double planning_time_s = 0.0;
};

// map.idl GridInfo, GridSnapshot and GridTiles: the mapper's grid and the patches between snapshots
// (decoded by common/core/grid_tiles.hpp).
struct GridInfo {
  uint32_t width = 0;   // cells
  uint32_t height = 0;  // cells
  double resolution = 0.0;
  Vec2 origin;  // map-frame position of cell (0, 0)'s lower-left corner
  double inflation_radius = 0.0;
};

struct GridSnapshot {
  uint32_t layout_id = 0;
  uint64_t version = 0;
  int64_t stamp_ns = 0;
  GridInfo info;
  std::vector<uint8_t> cells;  // row-major, width * height, cell classes (common/core/cell_class.hpp)
};

struct GridTiles {
  uint32_t layout_id = 0;
  uint64_t version = 0;
  int64_t stamp_ns = 0;
  uint16_t tile_side = 0;
  uint8_t encoding = 0;
  std::vector<uint32_t> tiles;
  std::vector<uint8_t> data;
};

// system.idl Heartbeat: every service's, once a second.
struct Heartbeat {
  std::string service;
  std::string instance_id;
  uint32_t pid = 0;
  std::string host;
  int64_t stamp_ns = 0;
  double uptime_s = 0.0;
  ServiceState state = ServiceState::Starting;
  std::vector<std::pair<std::string, int64_t>> counters;
};

// system.idl Alert: an operator alert's latest state, raised and cleared by the planners.
struct Alert {
  std::string alert_id;
  AlertKind kind = AlertKind::RobotOffline;
  std::string subject;    // the robot id, or SERVICE/INSTANCE
  bool active = false;    // false: cleared
  int64_t raised_ns = 0;  // wall clock when raised
  int64_t stamp_ns = 0;   // wall clock of this change
  std::string message;
  std::string raised_by;  // instance id of the planner that raised it
};

}  // namespace slam::msg
