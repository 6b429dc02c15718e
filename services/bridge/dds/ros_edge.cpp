// The ROS 2 DDS edge (see ros_edge.hpp).
#include "bridge/dds/ros_edge.hpp"

#include <spdlog/spdlog.h>

#include "bridge/core/foxglove_messages.hpp"

namespace slam::bridge {
namespace {

namespace gm = geometry_msgs::msg::dds_;

builtin_interfaces::msg::dds_::Time_ to_idl(const RosTime& t) {
  builtin_interfaces::msg::dds_::Time_ out;
  out.sec(t.sec);
  out.nanosec(t.nanosec);
  return out;
}

std_msgs::msg::dds_::Header_ header(const RosTime& stamp, const std::string& frame_id) {
  std_msgs::msg::dds_::Header_ out;
  out.stamp(to_idl(stamp));
  out.frame_id(frame_id);
  return out;
}

gm::Quaternion_ to_idl(const Quaternion& q) {
  gm::Quaternion_ out;
  out.x(q.x);
  out.y(q.y);
  out.z(q.z);
  out.w(q.w);
  return out;
}

RosPoseInput pose_input(const std_msgs::msg::dds_::Header_& h, const gm::Pose_& p) {
  const gm::Quaternion_& q = p.orientation();
  return {h.frame_id(), Vec2{p.position().x(), p.position().y()}, Quaternion{q.x(), q.y(), q.z(), q.w()}};
}

}  // namespace

RosEdge::RosEdge(const BridgeOptions& options, OperatorSink& goals, Counters& counters)
    : goals_(goals),
      poses_received_(counters.get("ros_poses_received")),
      poses_refused_(counters.get("ros_poses_refused")),
      face_(options.periods, options.ros_robot, *this) {}

Result<std::unique_ptr<RosEdge>> RosEdge::create(dds::Participant& p, const BridgeOptions& options,
                                                 OperatorSink& goals, Counters& counters) {
  std::unique_ptr<RosEdge> edge(new RosEdge(options, goals, counters));
  auto map = dds::make_writer(p, dds::kRosMap);
  if (!map) return Error{"writer for rt/map: " + map.message()};
  edge->map_writer_ = std::move(*map);
  auto tf = dds::make_writer(p, dds::kRosTf);
  if (!tf) return Error{"writer for rt/tf: " + tf.message()};
  edge->tf_writer_ = std::move(*tf);
  auto initial = dds::make_writer(p, dds::kInitialPose);
  if (!initial) return Error{"writer for InitialPose: " + initial.message()};
  edge->initial_pose_writer_ = std::move(*initial);

  RosEdge& e = *edge;
  auto goal_reader =
      dds::make_reader(p, dds::kRosGoalPose, [&e](const gm::PoseStamped_& s, const dds::fdds::SampleInfo&) {
        std::lock_guard lock(e.mutex_);
        e.goal_poses_.push_back(pose_input(s.header(), s.pose()));
      });
  if (!goal_reader) return Error{"reader for rt/goal_pose: " + goal_reader.message()};
  edge->goal_reader_ = std::move(*goal_reader);
  auto pose_reader = dds::make_reader(
      p, dds::kRosInitialPose, [&e](const gm::PoseWithCovarianceStamped_& s, const dds::fdds::SampleInfo&) {
        std::lock_guard lock(e.mutex_);
        e.initial_poses_.push_back(pose_input(s.header(), s.pose().pose()));
      });
  if (!pose_reader) return Error{"reader for rt/initialpose: " + pose_reader.message()};
  edge->initial_pose_reader_ = std::move(*pose_reader);
  spdlog::info("bridge: ROS 2 face on rt/map, rt/tf, rt/goal_pose, rt/initialpose (robot: {})",
               options.ros_robot.empty() ? "the nearest to the pose" : options.ros_robot);
  return edge;
}

void RosEdge::run_once(const FleetModel& fleet, const MapView& map, int64_t now_mono_ns, int64_t stamp_ns) {
  std::vector<RosPoseInput> goal_poses, initial_poses;
  {
    std::lock_guard lock(mutex_);
    std::swap(goal_poses, goal_poses_);
    std::swap(initial_poses, initial_poses_);
  }
  for (const auto& g : goal_poses) {
    bump(poses_received_);
    if (Status s = face_.goal_pose(fleet, g); !s) {
      bump(poses_refused_);
      log_.warn("goal_pose", "bridge: rt/goal_pose refused: {}", s.message());
    }
  }
  for (const auto& i : initial_poses) {
    bump(poses_received_);
    if (Status s = face_.initial_pose(fleet, i); !s) {
      bump(poses_refused_);
      log_.warn("initialpose", "bridge: rt/initialpose refused: {}", s.message());
    }
  }
  face_.publish(fleet, map, now_mono_ns, stamp_ns);
}

void RosEdge::publish_map(const OccupancyGridOut& grid) {
  nav_msgs::msg::dds_::OccupancyGrid_ msg;
  msg.header(header(grid.stamp, kMapFrame));
  nav_msgs::msg::dds_::MapMetaData_ info;
  info.map_load_time(to_idl(grid.stamp));
  info.resolution(grid.resolution);
  info.width(grid.width);
  info.height(grid.height);
  gm::Pose_ origin;
  origin.position().x(grid.origin.x);
  origin.position().y(grid.origin.y);
  origin.orientation().w(1.0);  // the grid is not rotated
  info.origin(origin);
  msg.info(info);
  msg.data(grid.data);
  if (!map_writer_->write(msg)) log_.warn("map", "bridge: rt/map not written");
}

void RosEdge::publish_tf(const std::vector<TransformOut>& transforms) {
  // rt/tf is volatile: with no reader the message would be serialized for no one.
  if (tf_writer_->matched_readers() == 0) return;
  tf2_msgs::msg::dds_::TFMessage_ msg;
  msg.transforms().reserve(transforms.size());
  for (const TransformOut& t : transforms) {
    gm::TransformStamped_ ts;
    ts.header(header(t.stamp, t.parent));
    ts.child_frame_id(t.child);
    ts.transform().translation().x(t.translation.x);
    ts.transform().translation().y(t.translation.y);
    ts.transform().rotation(to_idl(t.rotation));
    msg.transforms().push_back(std::move(ts));
  }
  if (!tf_writer_->write(msg)) log_.warn("tf", "bridge: rt/tf not written");
}

void RosEdge::send_initial_pose(const std::string& robot_id, const Pose& pose) {
  InitialPose request;
  request.request_id(pose_ids_.next());
  request.robot_id(robot_id);
  Pose2 p;
  p.x(pose.x);
  p.y(pose.y);
  p.theta(pose.theta);
  request.pose(p);
  if (!initial_pose_writer_->write(request))
    log_.warn("initial_pose", "bridge: initial pose for {} not written", robot_id);
  spdlog::info("bridge: initial pose for {} ({}, {}, {})", robot_id, pose.x, pose.y, pose.theta);
}

}  // namespace slam::bridge
