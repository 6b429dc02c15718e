#pragma once
// topics.hpp bound to the Fast DDS generated types: use these with dds::make_writer / make_reader.
#include <slam/fastdds/correctionPubSubTypes.h>
#include <slam/fastdds/mapPubSubTypes.h>
#include <slam/fastdds/mqttPubSubTypes.h>
#include <slam/fastdds/navPubSubTypes.h>
#include <slam/fastdds/robotPubSubTypes.h>
#include <slam/fastdds/ros2PubSubTypes.h>
#include <slam/fastdds/simPubSubTypes.h>
#include <slam/fastdds/systemPubSubTypes.h>

#include "common/fastdds/dds.hpp"

namespace slam::dds {

inline const Topic<RobotObservationBatch, RobotObservationBatchPubSubType> kRobotObservations{
    topics::kRobotObservations};
inline const Topic<RobotState, RobotStatePubSubType> kRobotState{topics::kRobotState};
inline const Topic<RobotOdometry, RobotOdometryPubSubType> kRobotOdometry{topics::kRobotOdometry};
inline const Topic<PoseCorrection, PoseCorrectionPubSubType> kPoseCorrection{topics::kPoseCorrection};
inline const Topic<InitialPose, InitialPosePubSubType> kInitialPose{topics::kInitialPose};
inline const Topic<PlacementAnswer, PlacementAnswerPubSubType> kPlacementAnswer{topics::kPlacementAnswer};
inline const Topic<GridSnapshot, GridSnapshotPubSubType> kGridSnapshot{topics::kGridSnapshot};
inline const Topic<GridTiles, GridTilesPubSubType> kGridTiles{topics::kGridTiles};
inline const Topic<GridConfig, GridConfigPubSubType> kGridConfig{topics::kGridConfig};
inline const Topic<MapEdit, MapEditPubSubType> kMapEdit{topics::kMapEdit};
inline const Topic<MapFileRequest, MapFileRequestPubSubType> kMapFileRequest{topics::kMapFileRequest};
inline const Topic<MapReply, MapReplyPubSubType> kMapReply{topics::kMapReply};
inline const Topic<NavGoal, NavGoalPubSubType> kNavGoal{topics::kNavGoal};
inline const Topic<NavMission, NavMissionPubSubType> kNavMission{topics::kNavMission};
inline const Topic<RobotPath, RobotPathPubSubType> kRobotPath{topics::kRobotPath};
inline const Topic<WaypointCommand, WaypointCommandPubSubType> kWaypointCommand{topics::kWaypointCommand};
inline const Topic<PathRequest, PathRequestPubSubType> kPathRequest{topics::kPathRequest};
inline const Topic<PathReply, PathReplyPubSubType> kPathReply{topics::kPathReply};
inline const Topic<MqttTraffic, MqttTrafficPubSubType> kMqttTraffic{topics::kMqttTraffic};
inline const Topic<MqttRequest, MqttRequestPubSubType> kMqttRequest{topics::kMqttRequest};
inline const Topic<MqttReply, MqttReplyPubSubType> kMqttReply{topics::kMqttReply};
inline const Topic<MqttSubscriptions, MqttSubscriptionsPubSubType> kMqttSubscriptions{
    topics::kMqttSubscriptions};
inline const Topic<SimControl, SimControlPubSubType> kSimControl{topics::kSimControl};
inline const Topic<SimReply, SimReplyPubSubType> kSimReply{topics::kSimReply};
inline const Topic<SimWorld, SimWorldPubSubType> kSimWorld{topics::kSimWorld};
inline const Topic<SimGroundTruth, SimGroundTruthPubSubType> kSimGroundTruth{topics::kSimGroundTruth};
inline const Topic<Heartbeat, HeartbeatPubSubType> kHeartbeat{topics::kHeartbeat};
inline const Topic<Alert, AlertPubSubType> kAlert{topics::kAlert};
inline const Topic<ForgetRobot, ForgetRobotPubSubType> kForgetRobot{topics::kForgetRobot};
inline const Topic<FleetDigest, FleetDigestPubSubType> kFleetDigest{topics::kFleetDigest};
inline const Topic<FleetPoints, FleetPointsPubSubType> kFleetPoints{topics::kFleetPoints};

inline const Topic<nav_msgs::msg::dds_::OccupancyGrid_, nav_msgs::msg::dds_::OccupancyGrid_PubSubType>
    kRosMap{topics::kRosMap};
inline const Topic<tf2_msgs::msg::dds_::TFMessage_, tf2_msgs::msg::dds_::TFMessage_PubSubType> kRosTf{
    topics::kRosTf};
inline const Topic<geometry_msgs::msg::dds_::PoseStamped_, geometry_msgs::msg::dds_::PoseStamped_PubSubType>
    kRosGoalPose{topics::kRosGoalPose};
inline const Topic<geometry_msgs::msg::dds_::PoseWithCovarianceStamped_,
                   geometry_msgs::msg::dds_::PoseWithCovarianceStamped_PubSubType>
    kRosInitialPose{topics::kRosInitialPose};

}  // namespace slam::dds
