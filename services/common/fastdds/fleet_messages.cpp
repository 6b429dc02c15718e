// Fast DDS samples -> the fleet's plain messages (see fleet_messages.hpp).
#include "common/fastdds/fleet_messages.hpp"

namespace slam::msg {
namespace {

// A plain enumeration has the IDL's values in the IDL's order when it ends on the IDL's last value,
// and its names table (common/core/fleet_messages.hpp) names each value.
template <class Plain, class Idl>
constexpr bool mirrors(Plain plain_last, Idl idl_last, std::size_t names) {
  return static_cast<uint32_t>(plain_last) == static_cast<uint32_t>(idl_last) &&
         names == static_cast<std::size_t>(idl_last) + 1;
}
static_assert(mirrors(GoalMode::Stop, slam::GOAL_STOP, kGoalModeNames.size()));
static_assert(mirrors(SquareAnchor::Centred, slam::SQUARE_CENTRED, kSquareAnchorNames.size()));
static_assert(mirrors(GoalStatus::Failed, slam::GOAL_STATUS_FAILED, kGoalStatusNames.size()));
static_assert(mirrors(MissionStatus::Cancelled, slam::MISSION_CANCELLED, kMissionStatusNames.size()));
static_assert(mirrors(PlanStatus::InvalidRequest, slam::PLAN_INVALID_REQUEST, kPlanStatusNames.size()));
static_assert(mirrors(PlanStatus::InvalidRequest, slam::PLAN_INVALID_REQUEST, kPlanStatusIds.size()));
static_assert(mirrors(CorrectionSource::Restored, slam::CORRECTION_RESTORED, kCorrectionSourceIds.size()));
static_assert(mirrors(CorrectionSource::Restored, slam::CORRECTION_RESTORED, kCorrectionSourceNames.size()));
static_assert(mirrors(RobotPlacement::Lost, slam::PLACEMENT_LOST, kRobotPlacementNames.size()));
static_assert(mirrors(ServiceState::Stopping, slam::SERVICE_STOPPING, kServiceStateNames.size()));
static_assert(mirrors(AlertKind::RobotLost, slam::ALERT_ROBOT_LOST, 4));  // named in alert_kind.hpp

template <class To, class From>
To cast(From value) {
  return static_cast<To>(static_cast<uint32_t>(value));
}

std::vector<Vec2> from_idl(const std::vector<slam::Point2>& points) {
  std::vector<Vec2> out;
  out.reserve(points.size());
  for (const slam::Point2& p : points) out.push_back(msg::from_idl(p));
  return out;
}

}  // namespace

GoalMode from_idl(slam::GoalMode m) {
  return cast<GoalMode>(m);
}
SquareAnchor from_idl(slam::SquareAnchor a) {
  return cast<SquareAnchor>(a);
}
GoalStatus from_idl(slam::GoalStatus s) {
  return cast<GoalStatus>(s);
}
MissionStatus from_idl(slam::MissionStatus s) {
  return cast<MissionStatus>(s);
}
PlanStatus from_idl(slam::PlanStatus s) {
  return cast<PlanStatus>(s);
}
CorrectionSource from_idl(slam::CorrectionSource s) {
  return cast<CorrectionSource>(s);
}
ServiceState from_idl(slam::ServiceState s) {
  return cast<ServiceState>(s);
}
AlertKind from_idl(slam::AlertKind k) {
  return cast<AlertKind>(k);
}

slam::GoalMode to_idl(GoalMode m) {
  return cast<slam::GoalMode>(m);
}
slam::GoalStatus to_idl(GoalStatus s) {
  return cast<slam::GoalStatus>(s);
}
slam::MissionStatus to_idl(MissionStatus s) {
  return cast<slam::MissionStatus>(s);
}
slam::PlanStatus to_idl(PlanStatus s) {
  return cast<slam::PlanStatus>(s);
}
slam::AlertKind to_idl(AlertKind k) {
  return cast<slam::AlertKind>(k);
}

Vec2 from_idl(const slam::Point2& p) {
  return {p.x(), p.y()};
}

Pose from_idl(const slam::Pose2& p) {
  return {p.x(), p.y(), p.theta()};
}

slam::Point2 to_idl(Vec2 v) {
  slam::Point2 p;
  p.x(v.x);
  p.y(v.y);
  return p;
}

RobotState from_idl(const slam::RobotState& s) {
  RobotState d;
  d.robot_id = s.robot_id().to_string();
  d.protocol_v2 = s.protocol() == slam::PROTOCOL_V2;
  d.online = s.presence() == slam::PRESENCE_ONLINE;
  d.pose = from_idl(s.pose());
  d.has_heading = s.has_heading();
  d.first_seen_ns = s.first_seen_ns();
  d.last_seen_ns = s.last_seen_ns();
  d.messages = s.messages();
  d.points = s.points();
  d.rejected = s.rejected();
  d.battery = s.battery();
  d.status = s.status().to_string();
  return d;
}

RobotPose from_idl(const slam::DigestRobot& r) {
  return {r.robot_id().to_string(), from_idl(r.pose()), r.has_heading(),
          r.presence() == slam::PRESENCE_ONLINE, r.last_seen_ns()};
}

PoseCorrection from_idl(const slam::PoseCorrection& c) {
  PoseCorrection d;
  d.robot_id = c.robot_id().to_string();
  d.version = c.version();
  d.stamp_ns = c.stamp_ns();
  d.map_from_odom = from_idl(c.map_from_odom());
  d.covariance = c.covariance();
  d.segment = c.segment();
  d.keyframes = c.keyframes();
  d.loop_closures = c.loop_closures();
  d.source = from_idl(c.source());
  d.placement = cast<RobotPlacement>(c.placement());
  d.localisation_score = c.localisation_score();
  return d;
}

RobotPath from_idl(const slam::RobotPath& p) {
  return {p.robot_id().to_string(),
          p.goal_id(),
          from_idl(p.mode()),
          from_idl(p.status()),
          from_idl(p.target()),
          from_idl(p.waypoints()),
          p.current(),
          p.reason().to_string()};
}

Mission from_idl(const slam::NavMission& m) {
  return {m.robot_id().to_string(),
          m.mission_id(),
          from_idl(m.waypoints()),
          m.loop(),
          m.current(),
          m.laps(),
          from_idl(m.status()),
          m.reason().to_string()};
}

PathReply from_idl(const slam::PathReply& r) {
  return {r.request_id(),     from_idl(r.status()), r.reason().to_string(),
          from_idl(r.path()), r.length_m(),         r.planning_time_s()};
}

GridSnapshot from_idl(const slam::GridSnapshot& s) {
  const slam::GridInfo& i = s.info();
  return {s.layout_id(), s.version(), s.stamp_ns(),
          GridInfo{i.width(), i.height(), i.resolution(), from_idl(i.origin()), i.inflation_radius()},
          s.cells()};
}

GridTiles from_idl(const slam::GridTiles& t) {
  return {t.layout_id(), t.version(), t.stamp_ns(), t.tile_side(), t.encoding(), t.tiles(), t.data()};
}

Heartbeat from_idl(const slam::Heartbeat& h) {
  Heartbeat d;
  d.service = h.service().to_string();
  d.instance_id = h.instance_id().to_string();
  d.pid = h.pid();
  d.host = h.host().to_string();
  d.stamp_ns = h.stamp_ns();
  d.uptime_s = h.uptime_s();
  d.state = from_idl(h.state());
  d.counters.reserve(h.counters().size());
  for (const slam::Counter& c : h.counters()) d.counters.emplace_back(c.name().to_string(), c.value());
  return d;
}

Alert from_idl(const slam::Alert& a) {
  return {a.alert_id().to_string(),
          from_idl(a.kind()),
          a.subject().to_string(),
          a.active(),
          a.raised_ns(),
          a.stamp_ns(),
          a.message().to_string(),
          a.raised_by().to_string()};
}

}  // namespace slam::msg
