#pragma once
// One non-trivial sample per IDL topic type (Fast DDS types): long sequences, non-ASCII strings,
// every enum away from its first value, keys set, so a lost or misaligned field shows.
#include "common/fastdds/fast_topics.hpp"

namespace slam::interop {

RobotObservationBatch sample_robot_observations();
RobotState sample_robot_state();
RobotOdometry sample_robot_odometry();
PoseCorrection sample_pose_correction();
InitialPose sample_initial_pose();
PlacementAnswer sample_placement_answer();
GridSnapshot sample_grid_snapshot();
GridTiles sample_grid_tiles();
GridConfig sample_grid_config();
MapEdit sample_map_edit();
MapFileRequest sample_map_file_request();
MapReply sample_map_reply();
NavGoal sample_nav_goal();
RobotPath sample_robot_path();
WaypointCommand sample_waypoint_command();
PathRequest sample_path_request();
PathReply sample_path_reply();
MqttTraffic sample_mqtt_traffic();
MqttRequest sample_mqtt_request();
MqttReply sample_mqtt_reply();
MqttSubscriptions sample_mqtt_subscriptions();
SimControl sample_sim_control();
SimReply sample_sim_reply();
SimWorld sample_sim_world();
SimGroundTruth sample_sim_ground_truth();
Heartbeat sample_heartbeat();
Alert sample_alert();
ForgetRobot sample_forget_robot();
FleetDigest sample_fleet_digest();
FleetPoints sample_fleet_points();
nav_msgs::msg::dds_::OccupancyGrid_ sample_ros_occupancy_grid();
tf2_msgs::msg::dds_::TFMessage_ sample_ros_tf_message();
geometry_msgs::msg::dds_::PoseStamped_ sample_ros_pose_stamped();
geometry_msgs::msg::dds_::PoseWithCovarianceStamped_ sample_ros_pose_with_covariance_stamped();

}  // namespace slam::interop
