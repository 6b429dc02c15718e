#pragma once
// The Fast DDS samples of the fleet's messages into their plain types (common/core/fleet_messages.hpp),
// and the enumerations both ways, for the DDS edges of the viewer, the bridge, slamctl and the
// planner. Enumerations convert by value: the plain ones keep the IDL's order (checked in the .cpp).
#include <slam/fastdds/correction.h>
#include <slam/fastdds/map.h>
#include <slam/fastdds/nav.h>
#include <slam/fastdds/robot.h>
#include <slam/fastdds/system.h>

#include "common/core/fleet_messages.hpp"

namespace slam::msg {

GoalMode from_idl(slam::GoalMode m);
SquareAnchor from_idl(slam::SquareAnchor a);
GoalStatus from_idl(slam::GoalStatus s);
MissionStatus from_idl(slam::MissionStatus s);
PlanStatus from_idl(slam::PlanStatus s);
CorrectionSource from_idl(slam::CorrectionSource s);
ServiceState from_idl(slam::ServiceState s);
AlertKind from_idl(slam::AlertKind k);

slam::GoalMode to_idl(GoalMode m);
slam::GoalStatus to_idl(GoalStatus s);
slam::MissionStatus to_idl(MissionStatus s);
slam::PlanStatus to_idl(PlanStatus s);
slam::AlertKind to_idl(AlertKind k);

Vec2 from_idl(const slam::Point2& p);
Pose from_idl(const slam::Pose2& p);
slam::Point2 to_idl(Vec2 v);

RobotState from_idl(const slam::RobotState& s);
RobotPose from_idl(const slam::DigestRobot& r);
PoseCorrection from_idl(const slam::PoseCorrection& c);
RobotPath from_idl(const slam::RobotPath& p);
Mission from_idl(const slam::NavMission& m);
PathReply from_idl(const slam::PathReply& r);
GridSnapshot from_idl(const slam::GridSnapshot& s);
GridTiles from_idl(const slam::GridTiles& t);
Heartbeat from_idl(const slam::Heartbeat& h);
Alert from_idl(const slam::Alert& a);

}  // namespace slam::msg
