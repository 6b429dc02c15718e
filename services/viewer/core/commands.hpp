#pragma once
// What the operator asks other services to do, as plain structs. Panels and click handling
// produce them; the DDS edge (viewer_node.cpp) turns them into IDL samples. Each send returns
// the request id it used, 0 when the middleware refused the sample.
#include <cstdint>
#include <string>
#include <vector>

#include "viewer/core/intake_types.hpp"

namespace slam::viewer {

struct GoalCommand {
  std::string robot_id;  // "*" for every robot
  GoalMode mode = GoalMode::Direct;
  Vec2 target;
  double square_size = 1.0;
  bool square_centred = false;
};

enum class MapEditKind : uint8_t { Obstruct, Unobstruct, ClearObstructions, ResetRobot };  // idl order

struct MapEditCommand {
  MapEditKind kind = MapEditKind::Obstruct;
  Vec2 point;
  std::string robot_id;
};

struct GridConfigCommand {
  double resolution = 0.05;
  Vec2 origin;
  double width_m = 20.0;
  double height_m = 20.0;
  double inflation_radius = 0.2;
  bool legacy_mode = false;
};

enum class MqttRequestKind : uint8_t { Publish, Subscribe, Unsubscribe };  // idl order

struct MqttRequestCommand {
  MqttRequestKind kind = MqttRequestKind::Publish;
  std::string topic;
  std::vector<uint8_t> payload;
  uint8_t qos = 0;
  bool retain = false;
};

enum class SimCommandKind : uint8_t {
  Spawn,
  Remove,
  Pause,
  Resume,
  SetWorld,
  SetNoise,
  SetSpeed
};  // idl order

struct SimCommand {
  SimCommandKind kind = SimCommandKind::Spawn;
  uint32_t count = 1;
  std::string robot_id;
  std::string world;
  double range_noise_sd = 0.01;
  double dropout = 0.0;
  double odometry_drift = 0.0;
  double speed_factor = 1.0;
};

struct MapFileCommand {
  bool import = false;
  std::string yaml_path;
};

// An operator's initial pose (InitialPose): `robot_id` is now at `pose` in the map frame.
struct InitialPoseCommand {
  std::string robot_id;
  Pose pose;
};

// An operator's answer to where the mapper is placing `robot_id` (PlacementAnswer).
struct PlacementAnswerCommand {
  std::string robot_id;
  bool accept = false;  // else rejected: searched for elsewhere
};

// Every gateway, planner and viewer drops the robot (ForgetRobot); its map data stays.
struct ForgetCommand {
  std::string robot_id;
};

// A path request (PathRequest) the viewer previews: drawn with its length, or the reason it failed.
struct PathPreviewCommand {
  Vec2 start;
  Vec2 goal;
  std::string algorithm = "astar";
};

// A list of waypoints for one robot, driven in order once or looped (NavMission).
struct MissionCommand {
  std::string robot_id;
  std::vector<Vec2> waypoints;
  bool loop = false;
};

class CommandSink {
 public:
  virtual ~CommandSink() = default;
  virtual uint64_t send(const GoalCommand& c) = 0;
  virtual uint64_t send(const MapEditCommand& c) = 0;
  virtual uint64_t send(const GridConfigCommand& c) = 0;
  virtual uint64_t send(const MqttRequestCommand& c) = 0;
  virtual uint64_t send(const SimCommand& c) = 0;
  virtual uint64_t send(const MapFileCommand& c) = 0;
  virtual uint64_t send(const InitialPoseCommand& c) = 0;
  virtual uint64_t send(const PlacementAnswerCommand& c) = 0;
  virtual uint64_t send(const ForgetCommand& c) = 0;
  virtual uint64_t send(const PathPreviewCommand& c) = 0;
  virtual uint64_t send(const MissionCommand& c) = 0;
};

}  // namespace slam::viewer
