#pragma once
// The bridge's ROS 2 face: the map and the robots' frames as ROS 2 messages (nav_msgs/OccupancyGrid
// on /map, tf2_msgs/TFMessage on /tf), and RViz2's "2D Goal Pose" and "2D Pose Estimate" back as a
// goal and an initial pose for one robot. Plain C++ with ROS field values: the DDS edge copies them
// into the idl/ros2.idl types. Reads the same FleetModel and MapView as the Foxglove face.
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "bridge/core/bridge_options.hpp"
#include "bridge/core/fleet_model.hpp"
#include "bridge/core/map_view.hpp"
#include "bridge/core/operator_requests.hpp"
#include "common/core/result.hpp"

namespace slam::bridge {

// builtin_interfaces/Time.
struct RosTime {
  int32_t sec = 0;
  uint32_t nanosec = 0;
};
RosTime ros_time(int64_t stamp_ns);

struct Quaternion {
  double x = 0.0, y = 0.0, z = 0.0, w = 1.0;
};
// A rotation of `theta` about z, and back (the yaw of any rotation, the tilt ignored).
Quaternion yaw_quaternion(double theta);
double yaw_of(const Quaternion& q);

// nav_msgs/OccupancyGrid's fields, in the "map" frame.
struct OccupancyGridOut {
  RosTime stamp;
  float resolution = 0.0f;
  uint32_t width = 0;
  uint32_t height = 0;
  Vec2 origin;               // cell (0, 0)'s lower-left corner; no rotation
  std::vector<int8_t> data;  // row-major: -1 unknown, 0 free, 50 inflated, 100 occupied
};
OccupancyGridOut occupancy_grid(const GridGeometry& geometry, std::span<const uint8_t> cells,
                                int64_t stamp_ns);

// geometry_msgs/TransformStamped's fields: map -> one robot.
struct TransformOut {
  RosTime stamp;
  std::string parent;
  std::string child;
  Vec2 translation;
  Quaternion rotation;
};
// map -> robot for every robot with a state, frame ids "map" and the robot id.
std::vector<TransformOut> robot_transforms(const FleetModel& fleet, int64_t stamp_ns);

// A pose from a ROS tool (PoseStamped, PoseWithCovarianceStamped): header.frame_id and the pose in it.
struct RosPoseInput {
  std::string frame_id;
  Vec2 position;
  Quaternion orientation;
};

// The robot a ROS tool's pose is for: `configured` (--ros-robot) when set, else the robot with a
// state nearest to `at` (RViz2's tools name no robot). An error when there is none.
Result<std::string> robot_for(const FleetModel& fleet, const std::string& configured, Vec2 at);

class RosSink {
 public:
  virtual ~RosSink() = default;
  virtual void publish_map(const OccupancyGridOut& grid) = 0;
  virtual void publish_tf(const std::vector<TransformOut>& transforms) = 0;
  virtual void send_goal(const GoalCommand& goal) = 0;
  // The mapper's set-pose request (InitialPose): `robot_id` is at `pose` in the map frame.
  virtual void send_initial_pose(const std::string& robot_id, const Pose& pose) = 0;
};

class RosFace {
 public:
  // `robot`: the --ros-robot option (empty: the nearest robot).
  RosFace(const ChannelPeriods& periods, std::string robot, RosSink& sink);

  // The whole map when it changed and map_full_s passed since the last one (the topic is transient
  // local, so a late RViz2 gets the last one at once); the frames when a robot moved and robots_s passed.
  void publish(const FleetModel& fleet, const MapView& map, int64_t now_mono_ns, int64_t stamp_ns);

  // RViz2's "2D Goal Pose": a planned goal for the chosen robot. Poses in another frame than "map"
  // are refused (the bridge knows no other frame).
  Status goal_pose(const FleetModel& fleet, const RosPoseInput& pose);
  // RViz2's "2D Pose Estimate": the chosen robot's initial pose.
  Status initial_pose(const FleetModel& fleet, const RosPoseInput& pose);

 private:
  int64_t map_period_ns_;
  int64_t tf_period_ns_;
  std::string robot_;
  RosSink& sink_;
  int64_t map_sent_ns_ = std::numeric_limits<int64_t>::min();
  std::optional<uint64_t> map_sent_revision_;
  int64_t tf_sent_ns_ = std::numeric_limits<int64_t>::min();
  std::optional<uint64_t> tf_sent_version_;
};

}  // namespace slam::bridge
