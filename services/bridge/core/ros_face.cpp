// The ROS 2 face (see ros_face.hpp).
#include "bridge/core/ros_face.hpp"

#include <cmath>

#include "bridge/core/foxglove_messages.hpp"

namespace slam::bridge {
namespace {

int64_t to_ns(double seconds) {
  return static_cast<int64_t>(seconds * 1e9);
}

// Whether `period_ns` has passed since `sent_ns` (the first time always).
bool period_passed(int64_t sent_ns, int64_t period_ns, int64_t now_ns) {
  return sent_ns == std::numeric_limits<int64_t>::min() || now_ns - sent_ns >= period_ns;
}

Status check_frame(const RosPoseInput& pose) {
  if (pose.frame_id.empty() || pose.frame_id == kMapFrame) return {};
  return Error{"a pose in frame '" + pose.frame_id + "': only '" + kMapFrame + "' is known"};
}

}  // namespace

RosTime ros_time(int64_t stamp_ns) {
  const int64_t sec = stamp_ns >= 0 ? stamp_ns / 1'000'000'000 : (stamp_ns - 999'999'999) / 1'000'000'000;
  return {static_cast<int32_t>(sec), static_cast<uint32_t>(stamp_ns - sec * 1'000'000'000)};
}

Quaternion yaw_quaternion(double theta) {
  return {0.0, 0.0, std::sin(theta / 2.0), std::cos(theta / 2.0)};
}

double yaw_of(const Quaternion& q) {
  return std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
}

OccupancyGridOut occupancy_grid(const GridGeometry& geometry, std::span<const uint8_t> cells,
                                int64_t stamp_ns) {
  OccupancyGridOut out;
  out.stamp = ros_time(stamp_ns);
  out.resolution = static_cast<float>(geometry.resolution);
  out.width = static_cast<uint32_t>(geometry.width);
  out.height = static_cast<uint32_t>(geometry.height);
  out.origin = geometry.origin;
  out.data.reserve(cells.size());
  for (uint8_t c : cells) out.data.push_back(occupancy_of(c));
  return out;
}

std::vector<TransformOut> robot_transforms(const FleetModel& fleet, int64_t stamp_ns) {
  std::vector<TransformOut> out;
  for (const auto& [id, robot] : fleet.robots()) {
    if (!robot.has_state) continue;
    const Pose& p = robot.state.pose;
    out.push_back({ros_time(stamp_ns), kMapFrame, id, Vec2{p.x, p.y}, yaw_quaternion(p.theta)});
  }
  return out;
}

Result<std::string> robot_for(const FleetModel& fleet, const std::string& configured, Vec2 at) {
  if (!configured.empty()) return configured;
  const std::string* nearest = nullptr;
  double best = 0.0;
  for (const auto& [id, robot] : fleet.robots()) {
    if (!robot.has_state) continue;
    const double dx = robot.state.pose.x - at.x, dy = robot.state.pose.y - at.y;
    const double d2 = dx * dx + dy * dy;
    if (!nearest || d2 < best) {
      nearest = &id;
      best = d2;
    }
  }
  if (!nearest) return Error{"no robot known yet (and no --ros-robot)"};
  return *nearest;
}

RosFace::RosFace(const ChannelPeriods& periods, std::string robot, RosSink& sink)
    : map_period_ns_(to_ns(periods.map_full_s)),
      tf_period_ns_(to_ns(periods.robots_s)),
      robot_(std::move(robot)),
      sink_(sink) {}

void RosFace::publish(const FleetModel& fleet, const MapView& map, int64_t now_mono_ns, int64_t stamp_ns) {
  if (map.has_grid() && map_sent_revision_ != map.revision() &&
      period_passed(map_sent_ns_, map_period_ns_, now_mono_ns)) {
    sink_.publish_map(occupancy_grid(map.geometry(), map.cells(), map.stamp_ns()));
    map_sent_revision_ = map.revision();
    map_sent_ns_ = now_mono_ns;
  }
  const uint64_t robots = fleet.versions().robots;
  if (tf_sent_version_ != robots && period_passed(tf_sent_ns_, tf_period_ns_, now_mono_ns)) {
    auto transforms = robot_transforms(fleet, stamp_ns);
    if (!transforms.empty()) sink_.publish_tf(transforms);
    tf_sent_version_ = robots;
    tf_sent_ns_ = now_mono_ns;
  }
}

Status RosFace::goal_pose(const FleetModel& fleet, const RosPoseInput& pose) {
  SLAM_TRY(check_frame(pose));
  auto robot = robot_for(fleet, robot_, pose.position);
  if (!robot) return robot.error();
  sink_.send_goal(GoalCommand{*robot, msg::GoalMode::Planned, pose.position});
  return {};
}

Status RosFace::initial_pose(const FleetModel& fleet, const RosPoseInput& pose) {
  SLAM_TRY(check_frame(pose));
  auto robot = robot_for(fleet, robot_, pose.position);
  if (!robot) return robot.error();
  sink_.send_initial_pose(*robot, Pose{pose.position.x, pose.position.y, yaw_of(pose.orientation)});
  return {};
}

}  // namespace slam::bridge
