#pragma once
// The bridge's ROS 2 DDS edge, beside the Foxglove one: writers of rt/map and rt/tf and readers of
// rt/goal_pose and rt/initialpose (idl/ros2.idl types, ROS 2's type names and QoS), around the
// plain RosFace. Readers only queue what they convert; run_once() on the bridge's loop hands the
// poses to the face and lets it publish what is due. Goals leave through the bridge's NavGoal
// writer (OperatorSink), initial poses as the mapper's set-pose request (InitialPose).
#include <memory>
#include <mutex>
#include <vector>

#include "bridge/core/bridge_options.hpp"
#include "bridge/core/foxglove_face.hpp"
#include "bridge/core/ros_face.hpp"
#include "common/core/counters.hpp"
#include "common/core/log.hpp"
#include "common/core/request_retry.hpp"
#include "common/fastdds/fast_topics.hpp"

namespace slam::bridge {

class RosEdge final : public RosSink {
 public:
  static Result<std::unique_ptr<RosEdge>> create(dds::Participant& participant, const BridgeOptions& options,
                                                 OperatorSink& goals, Counters& counters);

  void run_once(const FleetModel& fleet, const MapView& map, int64_t now_mono_ns, int64_t stamp_ns);

  void publish_map(const OccupancyGridOut& grid) override;
  void publish_tf(const std::vector<TransformOut>& transforms) override;
  void send_goal(const GoalCommand& goal) override { goals_.send_goal(goal); }
  void send_initial_pose(const std::string& robot_id, const Pose& pose) override;

 private:
  RosEdge(const BridgeOptions& options, OperatorSink& goals, Counters& counters);

  OperatorSink& goals_;
  std::atomic<int64_t>& poses_received_;
  std::atomic<int64_t>& poses_refused_;
  RateLimitedLog log_;
  RequestIdSource pose_ids_;
  RosFace face_;
  std::mutex mutex_;
  std::vector<RosPoseInput> goal_poses_;     // under mutex_
  std::vector<RosPoseInput> initial_poses_;  // under mutex_

  std::unique_ptr<dds::Writer<nav_msgs::msg::dds_::OccupancyGrid_>> map_writer_;
  std::unique_ptr<dds::Writer<tf2_msgs::msg::dds_::TFMessage_>> tf_writer_;
  std::unique_ptr<dds::Writer<InitialPose>> initial_pose_writer_;
  std::unique_ptr<dds::Reader<geometry_msgs::msg::dds_::PoseStamped_>> goal_reader_;
  std::unique_ptr<dds::Reader<geometry_msgs::msg::dds_::PoseWithCovarianceStamped_>> initial_pose_reader_;
};

}  // namespace slam::bridge
