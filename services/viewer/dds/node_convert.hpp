#pragma once
// IDL samples <-> the viewer's plain types, at the DDS edge only: the fleet's messages through
// common/fastdds/fleet_messages.hpp, the viewer's own here. Enumerations share the IDL order, so
// they convert by value.
#include "common/fastdds/fast_topics.hpp"
#include "common/fastdds/fleet_messages.hpp"
#include "viewer/core/commands.hpp"
#include "viewer/core/intake_types.hpp"

namespace slam::viewer {

using msg::from_idl;

ObservationData from_idl(const slam::RobotObservation& o);
MqttEntry from_idl(const slam::MqttTraffic& t);
MqttSubscriptionsData from_idl(const slam::MqttSubscriptions& s);
SimWorldData from_idl(const slam::SimWorld& w);
SimTruthData from_idl(const slam::SimGroundTruth& t);
MapReplyData from_idl(const slam::MapReply& r);
MqttReplyData from_idl(const slam::MqttReply& r);
SimReplyData from_idl(const slam::SimReply& r);
ForgetData from_idl(const slam::ForgetRobot& f);

slam::NavGoal to_idl(const GoalCommand& c, uint64_t goal_id);
slam::MapEdit to_idl(const MapEditCommand& c, uint64_t request_id);
slam::GridConfig to_idl(const GridConfigCommand& c, uint64_t request_id);
slam::MqttRequest to_idl(const MqttRequestCommand& c, uint64_t request_id);
slam::SimControl to_idl(const SimCommand& c, uint64_t command_id);
slam::MapFileRequest to_idl(const MapFileCommand& c, uint64_t request_id);
slam::InitialPose to_idl(const InitialPoseCommand& c, uint64_t request_id);
slam::PlacementAnswer to_idl(const PlacementAnswerCommand& c, uint64_t request_id);
slam::ForgetRobot to_idl(const ForgetCommand& c, uint64_t request_id);
slam::PathRequest to_idl(const PathPreviewCommand& c, uint64_t request_id);
slam::NavMission to_idl(const MissionCommand& c, uint64_t mission_id);

}  // namespace slam::viewer
